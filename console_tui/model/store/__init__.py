"""The records and where they are kept: the bounded store, record batches, packed texts, the
intake queue, late records placed by their stamps, searches over the store's columns."""

"""The rows shown: the view under the rules, each rule's answers per chunk, search, seek and marks."""

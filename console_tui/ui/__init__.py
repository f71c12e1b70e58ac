"""The Textual UI: reads the model, controls the sources."""

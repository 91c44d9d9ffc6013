// Tools land here (placeholder so the library has a source).

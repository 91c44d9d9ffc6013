// Scene loading lands here (placeholder so the library has a source).

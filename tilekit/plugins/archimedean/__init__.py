"""The archimedean family plugin."""

"""The isohedral family plugin."""

"""The wang family plugin."""

"""The substitution family plugin."""

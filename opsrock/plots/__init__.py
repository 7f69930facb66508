"""Figures: each function writes a PNG to an explicit path and returns it."""

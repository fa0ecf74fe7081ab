"""Boats that make waves: a hull's Kelvin wake, and the waves other boats feel (issue 31)."""

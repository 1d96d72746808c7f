"""Files: boundaries as CSV, written atomically."""

"""The ball in a groove (Halsey & Ertas): equilibria, regime boundaries, tracing, export."""

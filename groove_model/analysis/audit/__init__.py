"""The audit of the paper's quantitative claims."""

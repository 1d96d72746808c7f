"""Computations on the model: regime classification and the audit of the paper's claims."""

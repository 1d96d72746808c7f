"""Generic pseudo-arclength continuation of curves H(x) = 0, H: R^(n+1) -> R^n."""

"""The physics of the ball in a groove: parameters, equilibria, boundary equations, SI units."""

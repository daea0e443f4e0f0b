"""Fleet risk: the roll-away rate of a production population, what drives it, and the design that meets a target."""

"""Science workflow around membrane-flow: budding time, sweeps, critical values, continuation and
the flat-start threshold against the end time."""

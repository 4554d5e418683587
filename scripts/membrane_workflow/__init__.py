"""Science workflow around membrane-flow: budding time, sweeps, critical values."""

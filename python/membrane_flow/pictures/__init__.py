"""Pictures of runs: render (a surface to PNG with VTK), movie (MP4 of a series), history (energy,
conservation, bud observables against time) and study (an observable of a sweep against its parameter)."""

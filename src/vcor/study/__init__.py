"""Parameter studies: config checks, scenes and their grid points, shards, the runner, aggregation
into archived datasets, time histories, the work-precision study."""

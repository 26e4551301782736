"""Parameter studies of an FMU on Dask (`rigidfmu study STUDY`): the study file (spec),
the FMUs of its scene variants (fmus), what a worker runs (worker), the metrics
mini-language (metrics), the results' parts and consolidation (store), the plot (plot);
run holds the command."""

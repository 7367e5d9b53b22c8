"""meshrepair-batch: run one of the toolkit's tools over a folder, a glob or a list of models on Dask.

Modules: cli (options, main), inputs (finding models, naming outputs), runner (one model as a
limited child process; shipped to Dask workers by value), store (results.jsonl, resume, summary),
progress (the done/failed/remaining line), engine (the Dask client and the task loop).
"""

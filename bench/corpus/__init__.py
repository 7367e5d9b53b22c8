"""Corpus runner: runs one of our tools and its peers over a folder of models,
checks every output with our mesh-check, and writes results.jsonl + report.md."""

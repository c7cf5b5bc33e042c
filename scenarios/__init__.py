"""The embedded default scenario corpus (JSON files; see README.md here)."""

"""The scenario corpus: case files, loaded, validated against the schema, name-checked."""

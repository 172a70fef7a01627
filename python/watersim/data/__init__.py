"""Reference data shipped with WaterSim (see SOURCES.md in this folder)."""

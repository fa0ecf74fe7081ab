"""The pipeline and its data: the system of boats, its state, the force sum, the step."""

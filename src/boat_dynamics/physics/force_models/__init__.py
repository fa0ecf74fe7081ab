"""One module per force model, each a function returning force and torque."""

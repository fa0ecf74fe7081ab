"""A naval architect's runs of a boat: RAOs in regular waves, sea trials."""

"""Materials: constituents from the shipped data files and the rule of mixtures for a woven
laminate (``mixtures``)."""

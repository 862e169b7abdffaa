"""Modal test correlation and test planning: a measured test read and placed on the model,
correlated with its modes by shape; sensor positions planned by Effective Independence."""

; placeholder action model for the manifest tests

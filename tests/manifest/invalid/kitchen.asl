// placeholder plan library for the manifest tests

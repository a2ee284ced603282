"""Front ends: the command line (`ballcvt.interfaces.cli`) and the browser explorer
(`ballcvt.interfaces.ui`). They import the public API only."""

"""The ``linkwork`` command line."""

"""Bundled linkages drawing their shaking force (issue 37): rendered by `plans demo`."""

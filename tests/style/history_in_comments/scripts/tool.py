#!/usr/bin/env python3
"""A fixture docstring.
Used for Issue #3's reports: flagged."""
STAMP = "2026-11-27"  # a string may hold a date
# A plain comment with no history.

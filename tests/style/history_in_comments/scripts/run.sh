#!/usr/bin/env bash
echo 'it is #5'  # see cafe1234 for the speed-up: flagged
n=${#args[@]}    # a count, not an issue

#!/usr/bin/env bash
# The command-line checks live in test/cli/check_cli.sh (with the other tests); this name, which
# issues use, runs them.
exec bash "$(dirname "$0")/../test/cli/check_cli.sh" "$@"

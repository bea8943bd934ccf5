#!/usr/bin/env bash
# A caller's mistake is refused through one helper (include/spp/detail/invalid.hpp: detail::invalid,
# detail::invalid_option), never a hand-thrown std::invalid_argument: the rule of the style note ("expected X, got Y",
# naming where), kept by this check on the library, the command line and the Python binding.
set -euo pipefail
cd "$1"
# (comments may say what is thrown: only code before a // counts)
if hits=$(grep -rnE "^([^/]|/[^/])*throw std::invalid_argument" src apps python/bind include |
          grep -v "include/spp/detail/invalid.hpp"); then
  echo "std::invalid_argument thrown by hand (use detail::invalid or detail::invalid_option):"
  echo "$hits"
  exit 1
fi
echo "1 passed, 0 failed"

# ntn_add_model(): compiles a TOML model into a constexpr header for a target (filled in by the
# model compiler work).

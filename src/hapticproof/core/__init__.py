"""The vocabulary every layer shares: errors, canonical symbols, decisions and evidence,
lazy stages, and the one reader of user expressions."""

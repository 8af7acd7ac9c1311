"""UFL weak forms of tribofx (pure functions; no solving)."""

// Translation unit that carries the precompiled header (Catch2 + Eigen) shared by all tests.

//! Reading named files: regular files only, inside their allowed folder, within a bound.

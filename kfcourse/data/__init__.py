"""Logs of real robots (chapter 12), read into immutable records with their units."""

from .plaza import PLAZA_RUNS, PlazaLog, load_plaza

__all__ = ["PLAZA_RUNS", "PlazaLog", "load_plaza"]

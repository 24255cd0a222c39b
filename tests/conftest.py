import os

os.environ.setdefault("MPLBACKEND", "Agg")

from hypothesis import settings

settings.register_profile("dfa", max_examples=60, deadline=None)
settings.load_profile("dfa")

"""The fit's faces in words: ``summary_data`` (one summary as data) and ``text`` (the
Design-Expert style tables). Pages are drawn above, in :mod:`rsm_lrg.report`.
"""

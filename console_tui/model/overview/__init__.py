"""Counts over the rows shown: the timeline, storms, node statistics, search matches as rows."""

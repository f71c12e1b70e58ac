"""The systemd journal as a source of log records, read through ``journalctl -o json``.

- ``journal_location``: which command-line arguments name the journal (``journal:``,
  ``journal:UNIT``, ``journal:PATH``; a ``*.journal`` file or a journal directory);
- ``journalctl``: the query (``JournalQuery``: files or a directory, units, ``--since``,
  follow) and the ``journalctl`` process, its output read line by line, bounded;
- ``journal_source``: the live source (``JournalSource``): the journal followed, its
  entries as records into an ``IntakeQueue``, run in the intake process (kind ``journal``).

Journal files given as files are read by ``sources/files/journal_file.py``; entries become
records in ``model/formats/journal_entry.py``.
"""

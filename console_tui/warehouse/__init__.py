"""The log warehouse: where a fleet's logs are kept, outside the console.

The warehouse is an OpenTelemetry Collector (OTLP over HTTP) or the table ``otel_logs`` that
the Collector's ClickHouse exporter writes, in a ClickHouse server or in chDB (ClickHouse's
engine in this process, on a local directory). Here: its addresses (``address``), the table's
DDL and the SQL that reads a record back (``schema``), the clients (``otlp_http``,
``clickhouse``), the disk spool and the loop ``console-tui ship`` runs (``spool``,
``shipper``), and the rules as SQL (``pushdown``) with the queries that read a window of the
table page by page (``pages``). Records become OpenTelemetry log records in
``model.formats.otel_log``; the console reads the warehouse through
``sources.warehouse_source``. Nothing here knows ROS or the screen.
"""

"""The model: records, the store, levels, rules and formats. No ROS and no Textual here."""

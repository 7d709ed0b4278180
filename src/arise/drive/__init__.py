"""Put a driving agent in the ego's seat: run scenarios with it (`arise drive`) and
measure how it drove with SafeBench's metrics (`arise.drive.metrics`, docs/agents.md)."""

"""Renderings of ``studies.life``: text, JSON, CSV, ParaView series and pictures."""

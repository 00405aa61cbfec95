"""The event trace a run writes and every reader reads: CSV rows (trace), its .npz form
(trace_npz) and the per-output arrays (trace_view)."""

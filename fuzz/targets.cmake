# The fuzz targets: fuzz/<name>.cpp each, built as fuzz_<name> (fuzz/CMakeLists.txt), replayed
# by tests/fuzz, run by scripts/fuzz.sh (which reads this line).
set(A3_FUZZ_TARGETS episode scenario llm_reply model_request mcp_message dronecan fc_command)

// The MCP round trip of `a3rig mcp` on loopback, measured with the official MCP TypeScript SDK
// as the client: wall time from sending tools/call read_telemetry to its result (the call
// crosses the emulated link both ways and executes on the vehicle, in virtual time), and of
// ping (the transport and JSON-RPC alone), over stdio and over Streamable HTTP. Prints
// p50/p99/mean/max in milliseconds; figures, never pass/fail.
// Usage: node bench/mcp/mcp_roundtrip.mjs A3RIG [CALLS=500] [SCENARIO=survey-field]
import { spawn, spawnSync } from "node:child_process";
import { mkdtempSync, rmSync } from "node:fs";
import { createRequire } from "node:module";
import { tmpdir } from "node:os";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { performance } from "node:perf_hooks";

const here = dirname(fileURLToPath(import.meta.url));
const [a3rig, callsArg = "500", scenario = "survey-field"] = process.argv.slice(2);
const calls = Number(callsArg);
const kWarmup = 20;

function loadSdk() {
  const install = spawnSync("bash", [join(here, "../../tests/npm/install.sh")], { encoding: "utf8", stdio: ["ignore", "pipe", "inherit"] });
  if (install.status !== 0) throw new Error(`tests/npm/install.sh failed (status ${install.status}); the benchmark needs the MCP SDK`);
  const require = createRequire(join(install.stdout.trim().split("\n").pop(), "package.json"));
  return {
    Client: require("@modelcontextprotocol/sdk/client/index.js").Client,
    StdioClientTransport: require("@modelcontextprotocol/sdk/client/stdio.js").StdioClientTransport,
    StreamableHTTPClientTransport: require("@modelcontextprotocol/sdk/client/streamableHttp.js").StreamableHTTPClientTransport,
  };
}

function rigArgs(out) {
  return ["mcp", "--scenario", scenario, "--runtime", "virtual", "--out", out, "--quiet"];
}

function summary(samplesMs) {
  const sorted = [...samplesMs].sort((a, b) => a - b);
  const at = (q) => sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
  const mean = sorted.reduce((s, v) => s + v, 0) / sorted.length;
  return { n: sorted.length, p50: at(0.5), p99: at(0.99), mean, max: sorted[sorted.length - 1] };
}

async function measure(label, times, once) {
  for (let i = 0; i < kWarmup; ++i) await once();
  const samples = [];
  for (let i = 0; i < times; ++i) {
    const start = performance.now();
    await once();
    samples.push(performance.now() - start);
  }
  return { label, ...summary(samples) };
}

async function benchClient(client) {
  const outcomes = {};
  const telemetry = () => client.callTool({ name: "read_telemetry", arguments: {} }).then((r) => {
    const status = r.isError ? (r.structuredContent?.status ?? "error") : "ok";
    outcomes[status] = (outcomes[status] ?? 0) + 1;
  });
  const ping = await measure("ping", calls, () => client.ping());
  const call = await measure("tools/call read_telemetry", calls, telemetry);
  return [ping, { ...call, outcomes }];
}

async function overStdio(sdk, out) {
  const transport = new sdk.StdioClientTransport({ command: a3rig, args: rigArgs(out), stderr: "ignore" });
  const client = new sdk.Client({ name: "a3rig-mcp-bench", version: "1.0.0" });
  await client.connect(transport);
  const rows = await benchClient(client);
  await client.close();
  return rows.map((r) => ({ transport: "stdio", ...r }));
}

async function overHttp(sdk, out) {
  const rig = spawn(a3rig, [...rigArgs(out), "--http", "127.0.0.1:0"], { stdio: ["ignore", "ignore", "pipe"] });
  const url = await new Promise((resolve, reject) => {
    let seen = "";
    rig.stderr.on("data", (chunk) => {
      seen += chunk;
      const found = seen.match(/(http:\/\/127\.0\.0\.1:\d+\/mcp)/);
      if (found) resolve(found[1]);
    });
    rig.once("exit", (code) => reject(new Error(`a3rig mcp --http exited (${code}) before serving:\n${seen}`)));
  });
  const transport = new sdk.StreamableHTTPClientTransport(new URL(url));
  const client = new sdk.Client({ name: "a3rig-mcp-bench", version: "1.0.0" });
  await client.connect(transport);
  const rows = await benchClient(client);
  await transport.terminateSession();
  await client.close();
  await new Promise((resolve) => (rig.exitCode === null ? rig.once("exit", resolve) : resolve()));
  return rows.map((r) => ({ transport: "http", ...r }));
}

async function main() {
  if (!a3rig || !(calls > 0)) {
    console.error("usage: node bench/mcp/mcp_roundtrip.mjs A3RIG [CALLS=500] [SCENARIO=survey-field]");
    process.exit(2);
  }
  const sdk = loadSdk();
  const scratch = mkdtempSync(join(tmpdir(), "a3rig-mcp-bench-"));
  try {
    const rows = [...(await overStdio(sdk, join(scratch, "stdio"))), ...(await overHttp(sdk, join(scratch, "http")))];
    console.log(`MCP round trip, a3rig mcp --scenario ${scenario} --runtime virtual, loopback, ${calls} calls each ` +
                `after ${kWarmup} warm-up, node ${process.version}`);
    console.log("transport  request                      p50 ms   p99 ms  mean ms   max ms  outcomes");
    for (const r of rows)
      console.log(`${r.transport.padEnd(10)} ${r.label.padEnd(27)} ${[r.p50, r.p99, r.mean, r.max].map((v) => v.toFixed(3).padStart(8)).join(" ")}` +
                  (r.outcomes ? `  ${JSON.stringify(r.outcomes)}` : ""));
  } finally {
    rmSync(scratch, { recursive: true, force: true });
  }
}

main().catch((error) => {
  console.error(`mcp_roundtrip: ${error.stack ?? error}`);
  process.exit(1);
});

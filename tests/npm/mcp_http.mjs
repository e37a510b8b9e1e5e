// The official MCP TypeScript SDK as a client of `a3rig mcp --http` over Streamable HTTP: the
// test starts the rig on a free loopback port, the client lists the tools and the brief, pings,
// flies parcel-delivery to success, deletes its session (the rig then exits 0), and checks the
// episode with `a3rig validate`. Exit 0 pass, 1 fail, 77 skipped (npm unavailable).
import { spawn } from "node:child_process";
import { mkdirSync, rmSync } from "node:fs";
import { join } from "node:path";
import * as mcp from "./mcp_common.mjs";

// Starts `a3rig mcp --http 127.0.0.1:0` and resolves with the URL it prints on stderr.
function startRig(a3rig, out) {
  const rig = spawn(a3rig, ["mcp", "--scenario", "parcel-delivery", "--runtime", "virtual", "--out", out,
                            "--http", "127.0.0.1:0"], { stdio: ["ignore", "inherit", "pipe"] });
  const exited = new Promise((resolve) => rig.once("exit", (code, signal) => resolve({ code, signal })));
  const url = new Promise((resolve, reject) => {
    let seen = "";
    rig.stderr.on("data", (chunk) => {
      process.stderr.write(chunk);
      seen += chunk;
      const found = seen.match(/(http:\/\/127\.0\.0\.1:\d+\/mcp)/);
      if (found) resolve(found[1]);
    });
    exited.then(({ code }) => reject(new Error(`a3rig mcp --http exited (${code}) before serving`)));
  });
  return { rig, url, exited };
}

async function main() {
  const { a3rig, scratch } = mcp.parseArgs();
  const sdk = mcp.loadMcpSdk(mcp.installSdk());
  const out = join(scratch, "mcp-http");
  rmSync(out, { recursive: true, force: true });
  mkdirSync(out, { recursive: true });
  const { rig, url, exited } = startRig(a3rig, out);
  try {
    const transport = new sdk.StreamableHTTPClientTransport(new URL(await url));
    const client = new sdk.Client({ name: "a3rig-sdk-test-http", version: "1.0.0" });
    await client.connect(transport);
    mcp.check(transport.sessionId?.length > 0, "the server issued an Mcp-Session-Id");
    mcp.check(transport.protocolVersion === "2025-06-18", `protocol 2025-06-18 negotiated (got ${transport.protocolVersion})`);
    const { log, ending } = await mcp.flyWholeSession(client);
    await transport.terminateSession();
    await client.close();
    const { code } = await exited;
    mcp.check(code === 0, `a3rig mcp exits 0 after the session is deleted (got ${code})`);
    const episode = mcp.checkEpisode(a3rig, join(out, "episode.json"));
    console.log(`mcp http: ${log.length} calls; ${ending}; success ${episode.success}, ${episode.dialogue.length} turns`);
  } finally {
    if (rig.exitCode === null) rig.kill("SIGTERM");
  }
}

main().catch((error) => {
  console.error(`mcp http: FAILED: ${error.stack ?? error}`);
  process.exit(1);
});

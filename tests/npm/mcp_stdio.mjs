// The official MCP TypeScript SDK as a client of `a3rig mcp` over stdio: it spawns the rig,
// lists the tools and the brief, pings, flies parcel-delivery to success, closes, and checks
// the episode with `a3rig validate`. Exit 0 pass, 1 fail, 77 skipped (npm unavailable).
import { mkdirSync, rmSync } from "node:fs";
import { join } from "node:path";
import * as mcp from "./mcp_common.mjs";

async function main() {
  const { a3rig, scratch } = mcp.parseArgs();
  const sdk = mcp.loadMcpSdk(mcp.installSdk());
  const out = join(scratch, "mcp-stdio");
  rmSync(out, { recursive: true, force: true });
  mkdirSync(out, { recursive: true });
  const transport = new sdk.StdioClientTransport({
    command: a3rig,
    args: ["mcp", "--scenario", "parcel-delivery", "--runtime", "virtual", "--out", out],
    env: { ...process.env },
    stderr: "inherit",
  });
  const client = new sdk.Client({ name: "a3rig-sdk-test-stdio", version: "1.0.0" });
  await client.connect(transport);
  mcp.check(client.getServerVersion()?.name?.length > 0, "serverInfo has a name");
  const { log, ending } = await mcp.flyWholeSession(client);
  await client.close();
  const episode = mcp.checkEpisode(a3rig, join(out, "episode.json"));
  console.log(`mcp stdio: ${log.length} calls; ${ending}; success ${episode.success}, ${episode.dialogue.length} turns`);
}

main().catch((error) => {
  console.error(`mcp stdio: FAILED: ${error.stack ?? error}`);
  process.exit(1);
});

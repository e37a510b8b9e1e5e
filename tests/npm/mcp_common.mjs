// Shared steps of the MCP SDK client tests (mcp_stdio.mjs, mcp_http.mjs): install the pinned
// official MCP TypeScript SDK (install.sh; exit 77 = skip), check what `a3rig mcp` lists,
// fly parcel-delivery to success turn by turn, and check the written episode with
// `a3rig validate`. Every failed check throws an Error saying what and where.
import { spawnSync } from "node:child_process";
import { createRequire } from "node:module";
import { readFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

export const kSkip = 77;
const here = dirname(fileURLToPath(import.meta.url));

// Runs tests/npm/install.sh; exits 77 (ctest's skip) when it says npm cannot be used.
export function installSdk() {
  const run = spawnSync("bash", [join(here, "install.sh")], { encoding: "utf8", stdio: ["ignore", "pipe", "inherit"] });
  if (run.status === kSkip) {
    console.error("mcp sdk test: skipped, npm packages cannot be installed (see install.sh above)");
    process.exit(kSkip);
  }
  if (run.status !== 0) throw new Error(`tests/npm/install.sh failed with status ${run.status}`);
  return run.stdout.trim().split("\n").pop();
}

// The SDK's client modules, resolved from the cache folder install.sh printed.
export function loadMcpSdk(cacheDir) {
  const require = createRequire(join(cacheDir, "package.json"));
  return {
    Client: require("@modelcontextprotocol/sdk/client/index.js").Client,
    StdioClientTransport: require("@modelcontextprotocol/sdk/client/stdio.js").StdioClientTransport,
    StreamableHTTPClientTransport: require("@modelcontextprotocol/sdk/client/streamableHttp.js").StreamableHTTPClientTransport,
  };
}

export function check(condition, what) {
  if (!condition) throw new Error(`check failed: ${what}`);
}

// tools/list: the registry, A2A tasks included, each with an object input schema.
export async function checkTools(client) {
  const { tools } = await client.listTools();
  const names = tools.map((t) => t.name);
  for (const needed of ["read_telemetry", "takeoff", "navigate_to", "return_to_home", "report_turn"])
    check(names.includes(needed), `tools/list has ${needed} (got ${names.join(", ")})`);
  check(names.some((n) => n.startsWith("a2a_")), `tools/list has A2A tasks as a2a_<task> (got ${names.join(", ")})`);
  for (const tool of tools) check(tool.inputSchema?.type === "object", `${tool.name} has an object inputSchema`);
  return names;
}

// The brief: the server's instructions and the a3rig://mission resource.
export async function checkBrief(client) {
  check((client.getInstructions() ?? "").length > 0, "initialize carried instructions (the brief)");
  const { resources } = await client.listResources();
  check(resources.some((r) => r.uri === "a3rig://mission"), `resources/list has a3rig://mission (got ${JSON.stringify(resources)})`);
  const { contents } = await client.readResource({ uri: "a3rig://mission" });
  check(contents[0]?.text?.length > 0, "a3rig://mission has text");
  return contents[0].text;
}

const kLong = { timeout: 600000, resetTimeoutOnProgress: true };

// One call; `expectOk` false allows isError. Returns the CallToolResult.
async function call(client, log, name, args, expectOk = true) {
  let progress = 0;
  const result = await client.callTool({ name, arguments: args }, undefined, { ...kLong, onprogress: () => ++progress });
  log.push(`${name} ${JSON.stringify(args)} -> ${result.isError ? "ERROR " : ""}${result.content?.[0]?.text?.slice(0, 160)}` +
           (progress ? ` (${progress} progress)` : ""));
  check(Array.isArray(result.content) && result.content[0]?.type === "text", `${name}: text content`);
  if (expectOk) check(!result.isError, `${name} succeeds: ${result.content?.[0]?.text}`);
  return result;
}

const turn = (intent, text) => ({ intent, text });

// parcel-delivery: check telemetry, take off, fly to the drop point and descend over it, come
// home, land; each turn ended with report_turn, whose result is the supervisor's reply.
export async function flyParcelDelivery(client) {
  const log = [];
  try {
    const unknown = await call(client, log, "no_such_tool", {}, false).catch((e) => ({ rejected: e }));
    check(unknown.rejected || unknown.isError, "an unknown tool is refused");
    await call(client, log, "read_telemetry", {});
    const first = await call(client, log, "report_turn", turn("preflight_check", "Telemetry checked; ready to launch."));
    check(first.structuredContent && typeof first.structuredContent === "object", "report_turn returns the supervisor's reply as structuredContent");
    await call(client, log, "takeoff", { altitude_m: 50 });
    await call(client, log, "navigate_to", { waypoints: [[600, 400, 50], [600, 400, 5]] });
    await call(client, log, "report_turn", turn("deliver_package", "Flying the parcel to the drop point."));
    await call(client, log, "return_to_home", {});
    await call(client, log, "report_turn", turn("return_to_home", "Parcel delivered; returning home to land."));
    let reply = {};
    for (let t = 0; t < 4 && !reply.dialogue_over; ++t) {
      await call(client, log, "read_telemetry", {});
      reply = (await call(client, log, "report_turn", turn("confirm_landing", "Landed at home."))).structuredContent ?? {};
    }
    check(reply.dialogue_over === true, `the dialogue ends after landing (last reply ${JSON.stringify(reply)})`);
  } catch (error) {
    error.message += `\ntranscript:\n${log.join("\n")}`;
    throw error;
  }
  return log;
}

// After the dialogue the rig lands and writes the episode; then every call answers isError
// naming its status. Polls until then and returns that text.
export async function waitForEpisodeWritten(client, timeoutMs = 240000) {
  const start = Date.now();
  while (Date.now() - start < timeoutMs) {
    const result = await client.callTool({ name: "read_telemetry", arguments: {} }, undefined, kLong);
    if (result.isError && /completed|interrupted|failed/.test(result.content[0].text)) return result.content[0].text;
    await new Promise((r) => setTimeout(r, 200));
  }
  throw new Error(`the episode was not written within ${timeoutMs} ms`);
}

// The session both transports run once connected: the tool list and the brief checked, a ping,
// parcel-delivery flown to its end, the episode written, a ping after it. Returns the calls'
// log and the text the calls answer once the episode is written.
export async function flyWholeSession(client) {
  await checkTools(client);
  await checkBrief(client);
  await client.ping();
  const log = await flyParcelDelivery(client);
  const ending = await waitForEpisodeWritten(client);
  await client.ping();
  return { log, ending };
}

// `a3rig validate` accepts the episode and it is a success flown by the MCP agent.
export function checkEpisode(a3rig, episodePath) {
  const run = spawnSync(a3rig, ["validate", episodePath], { encoding: "utf8" });
  check(run.status === 0, `a3rig validate ${episodePath} exits 0 (status ${run.status}):\n${run.stdout}${run.stderr}`);
  const episode = JSON.parse(readFileSync(episodePath, "utf8"));
  check(episode.success === true, `the episode is a success (success: ${episode.success})`);
  check(episode._meta?.model === "a3rig/mcp", `the episode was flown by the MCP agent (_meta.model ${episode._meta?.model})`);
  return episode;
}

// argv: <a3rig binary> <scratch folder>
export function parseArgs() {
  const [a3rig, scratch] = process.argv.slice(2);
  if (!a3rig || !scratch) {
    console.error("usage: node mcp_<transport>.mjs A3RIG_BINARY SCRATCH_DIR");
    process.exit(2);
  }
  return { a3rig, scratch };
}

// The official OpenAI SDK (`openai` on npm, pinned in package.json) against
// `a3rig serve-model --responder scripted`: a client nobody here wrote must get what it expects
// from an OpenAI-compatible server. Non-streaming and streaming chat (with usage), tools with
// tool_choice "required", response_format json_object and json_schema, n, models.retrieve /
// models.list, and errors thrown as the SDK's own classes (400, 401, 404).
// Run through run_node_test.sh (ctest -L npm); A3RIG is the a3rig program.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import { requireSdk } from './sdk.mjs';

const openaiModule = requireSdk('openai');
const OpenAI = openaiModule.OpenAI ?? openaiModule.default ?? openaiModule;

const KEY = 'sk-a3rig-npm-test';
let server; // { process, baseURL, dir }

// Starts serve-model on a free port; resolves once its --ready-file names the port.
async function startServeModel(extraArgs, env) {
  const a3rig = process.env.A3RIG;
  assert.ok(a3rig && fs.existsSync(a3rig), `A3RIG must name the a3rig program (got ${a3rig})`);
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'a3-npm-openai-'));
  const ready = path.join(dir, 'port');
  const child = spawn(a3rig, ['serve-model', '--responder', 'scripted', '--port', '0', '--ready-file', ready,
                              '--quiet', ...extraArgs], { env: { ...process.env, ...env }, stdio: ['ignore', 'pipe', 'pipe'] });
  let stderr = '';
  child.stderr.on('data', (d) => { stderr += d; });
  for (let i = 0; i < 500; ++i) {
    if (fs.existsSync(ready)) {
      const port = Number(fs.readFileSync(ready, 'utf8').trim());
      if (port > 0) return { process: child, baseURL: `http://127.0.0.1:${port}/v1`, dir };
    }
    if (child.exitCode !== null) break;
    await new Promise((r) => setTimeout(r, 20));
  }
  child.kill('SIGTERM');
  throw new Error(`serve-model did not come up: ${stderr}`);
}

function client(apiKey = KEY) {
  return new OpenAI({ baseURL: server.baseURL, apiKey, maxRetries: 0, timeout: 30_000 });
}

const user = (content) => [{ role: 'user', content }];

before(async () => {
  server = await startServeModel(['--require-key-env', 'A3_NPM_TEST_KEY', '--model-id', 'scripted',
                                  '--model-id', 'a3rig-test-model', '--latency', 'fixed:0.2'],
                                 { A3_NPM_TEST_KEY: KEY });
});

after(async () => {
  if (!server) return;
  const exited = new Promise((r) => server.process.once('exit', r));
  server.process.kill('SIGTERM');
  await exited;
  assert.equal(server.process.exitCode, 0, 'serve-model stops cleanly on SIGTERM');
  fs.rmSync(server.dir, { recursive: true, force: true });
});

test('non-streaming chat completion', async () => {
  const r = await client().chat.completions.create({ model: 'scripted', messages: user('Say hello.') });
  assert.equal(r.object, 'chat.completion');
  assert.equal(r.model, 'scripted');
  assert.equal(r.choices.length, 1);
  assert.equal(r.choices[0].message.role, 'assistant');
  assert.equal(typeof r.choices[0].message.content, 'string');
  assert.ok(r.choices[0].message.content.length > 0);
  assert.equal(r.choices[0].finish_reason, 'stop');
  assert.ok(r.usage.total_tokens > 0);
  assert.equal(r.usage.total_tokens, r.usage.prompt_tokens + r.usage.completion_tokens);
});

test('n choices', async () => {
  const r = await client().chat.completions.create({ model: 'scripted', messages: user('Hi.'), n: 3 });
  assert.deepEqual(r.choices.map((c) => c.index), [0, 1, 2]);
});

test('streaming chat completion with usage', async () => {
  const started = Date.now();
  const stream = await client().chat.completions.create({
    model: 'scripted', messages: user('Say hello.'), stream: true, stream_options: { include_usage: true },
  });
  let text = '';
  let contentChunks = 0;
  let role = null;
  let finish = null;
  let usage = null;
  for await (const chunk of stream) {
    assert.equal(chunk.object, 'chat.completion.chunk');
    if (chunk.usage) usage = chunk.usage;
    if (chunk.choices.length === 0) continue;
    const delta = chunk.choices[0].delta;
    if (delta.role) role = delta.role;
    if (delta.content) { text += delta.content; ++contentChunks; }
    if (chunk.choices[0].finish_reason) finish = chunk.choices[0].finish_reason;
  }
  assert.equal(role, 'assistant');
  assert.ok(contentChunks >= 2, `content in pieces (${contentChunks} chunks)`);
  const whole = await client().chat.completions.create({ model: 'scripted', messages: user('Say hello.') });
  assert.equal(text, whole.choices[0].message.content);
  assert.equal(finish, 'stop');
  assert.ok(usage && usage.total_tokens > 0, 'a usage chunk with include_usage');
  assert.ok(Date.now() - started >= 190, 'the latency (0.2 s) is spent over the stream');
});

test('tools with tool_choice "required" give tool calls with parseable arguments', async () => {
  const tools = [{
    type: 'function',
    function: {
      name: 'get_weather',
      description: 'Weather at a place',
      parameters: {
        type: 'object',
        properties: {
          city: { type: 'string' },
          days: { type: 'integer', minimum: 1, maximum: 7 },
          unit: { type: 'string', enum: ['celsius', 'fahrenheit'] },
        },
        required: ['city', 'days', 'unit'],
        additionalProperties: false,
      },
    },
  }];
  const r = await client().chat.completions.create({
    model: 'scripted', messages: user('Weather in Oulu?'), tools, tool_choice: 'required',
  });
  const choice = r.choices[0];
  assert.equal(choice.finish_reason, 'tool_calls');
  assert.equal(choice.message.tool_calls.length, 1);
  const call = choice.message.tool_calls[0];
  assert.equal(call.type, 'function');
  assert.match(call.id, /^call_/);
  assert.equal(call.function.name, 'get_weather');
  const args = JSON.parse(call.function.arguments);
  assert.equal(typeof args.city, 'string');
  assert.ok(Number.isInteger(args.days) && args.days >= 1 && args.days <= 7);
  assert.equal(args.unit, 'celsius');

  // The same streamed: the SDK's stream helper puts the call back together.
  const stream = client().chat.completions.stream({
    model: 'scripted', messages: user('Weather in Oulu?'), tools, tool_choice: 'required',
  });
  const final = await stream.finalChatCompletion();
  assert.equal(final.choices[0].message.tool_calls[0].function.name, 'get_weather');
  assert.deepEqual(JSON.parse(final.choices[0].message.tool_calls[0].function.arguments), args);
});

test('response_format json_object and json_schema', async () => {
  const asObject = await client().chat.completions.create({
    model: 'scripted', messages: user('Reply in JSON.'), response_format: { type: 'json_object' },
  });
  const parsed = JSON.parse(asObject.choices[0].message.content);
  assert.equal(typeof parsed, 'object');
  assert.ok(parsed !== null && !Array.isArray(parsed));

  const schema = {
    type: 'object',
    properties: { answer: { type: 'string' }, confidence: { type: 'number', minimum: 0, maximum: 1 } },
    required: ['answer', 'confidence'],
    additionalProperties: false,
  };
  const asSchema = await client().chat.completions.create({
    model: 'scripted', messages: user('Reply.'),
    response_format: { type: 'json_schema', json_schema: { name: 'reply', schema, strict: true } },
  });
  const value = JSON.parse(asSchema.choices[0].message.content);
  assert.deepEqual(Object.keys(value).sort(), ['answer', 'confidence']);
  assert.equal(typeof value.answer, 'string');
  assert.ok(value.confidence >= 0 && value.confidence <= 1);
});

test('models.retrieve and models.list', async () => {
  const model = await client().models.retrieve('a3rig-test-model');
  assert.equal(model.id, 'a3rig-test-model');
  assert.equal(model.object, 'model');
  assert.equal(typeof model.created, 'number');
  assert.equal(model.owned_by, 'a3rig');
  const ids = [];
  for await (const m of client().models.list()) ids.push(m.id);
  assert.deepEqual(ids, ['scripted', 'a3rig-test-model']);
  await assert.rejects(client().models.retrieve('gpt-none'), (e) => {
    assert.ok(e instanceof OpenAI.NotFoundError, `NotFoundError, got ${e?.constructor?.name}`);
    assert.equal(e.status, 404);
    assert.equal(e.code, 'model_not_found');
    return true;
  });
});

test('a bad request throws BadRequestError with the status, message, param and code', async () => {
  await assert.rejects(
    client().chat.completions.create({ model: 'scripted', messages: user('Hi.'), n: 42 }),
    (e) => {
      assert.ok(e instanceof OpenAI.BadRequestError, `BadRequestError, got ${e?.constructor?.name}`);
      assert.equal(e.status, 400);
      assert.match(e.message, /'n' must be an integer from 1 to 8/);
      assert.equal(e.param, 'n');
      assert.equal(e.code, 'invalid_value');
      assert.equal(e.type, 'invalid_request_error');
      return true;
    });
  await assert.rejects(
    client().chat.completions.create({ model: 'scripted', messages: user('Hi.'), logprobs: true }),
    (e) => e instanceof OpenAI.BadRequestError && e.param === 'logprobs');
});

test('a wrong key throws AuthenticationError (401)', async () => {
  await assert.rejects(client('sk-wrong').chat.completions.create({ model: 'scripted', messages: user('Hi.') }), (e) => {
    assert.ok(e instanceof OpenAI.AuthenticationError, `AuthenticationError, got ${e?.constructor?.name}`);
    assert.equal(e.status, 401);
    assert.equal(e.code, 'invalid_api_key');
    return true;
  });
});

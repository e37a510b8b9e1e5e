// a3rig episode report: draws the map, the timelines, the score and the dialogue of one episode
// from the JSON in #a3-data (written by `a3rig report`), with d3 v3 (Debian's libjs-d3).
// A rig episode has a trajectory and timed turns (mission seconds); a corpus episode has
// neither, and its timelines run over the turn number.
(function () {
  'use strict';
  var data = JSON.parse(document.getElementById('a3-data').textContent);
  var ep = data.episode || {};
  var rig = ep._rig || {};
  var world = data.world || null;
  var dialogue = ep.dialogue || [];
  var rigTurns = rig.turns || [];
  var samples = (rig.trajectory && rig.trajectory.samples_1hz) || [];
  var events = rig.safety_events || [];
  var timed = rigTurns.length === dialogue.length && rigTurns.length > 0 && rigTurns[0].started_s !== undefined;
  var turnColour = d3.scale.category10();
  var eventColour = d3.scale.category20();

  // ---- time ----------------------------------------------------------------------------
  // Each turn's span on the timeline axis: mission seconds for a rig episode, turn number else.
  function turnSpan(i) {
    if (timed) {
      var r = rigTurns[i];
      return { start: r.started_s, decided: r.decided_s, sent: r.sent_s, delivered: r.delivered_s, end: r.finished_s };
    }
    return { start: i, decided: i + 0.5, sent: i + 0.5, delivered: i + 0.5, end: i + 1 };
  }
  function timeEnd() {
    var end = 1;
    if (samples.length) end = Math.max(end, samples[samples.length - 1][0]);
    if (dialogue.length) end = Math.max(end, turnSpan(dialogue.length - 1).end || 0);
    if (rig.mission_time_s) end = Math.max(end, rig.mission_time_s);
    return end;
  }
  var T = timeEnd();
  var timeUnit = timed || samples.length ? 's' : 'turn';
  function turnAt(t) {
    var at = -1;
    for (var i = 0; i < dialogue.length; ++i) if (turnSpan(i).start <= t) at = i;
    return at;
  }
  function agentTurnIndices() {
    var out = [];
    dialogue.forEach(function (turn, i) { if (turn.speaker === 'agent') out.push(i); });
    return out;
  }

  // ---- header --------------------------------------------------------------------------
  function fmt(x, digits) { return x === null || x === undefined ? '–' : (+x).toFixed(digits); }
  function drawHeader() {
    d3.select('#title').text(data.title || 'episode');
    var s = d3.select('#summary');
    var status = rig.status || (ep._meta && ep._meta.generation_failed ? 'generation_failed' : 'corpus episode');
    s.append('span').attr('class', ep.success ? 'good' : 'bad').text(ep.success ? 'success' : 'no success');
    s.append('span').text('status: ' + status);
    if (data.score && data.score.valid) s.append('span').text('α³ = ' + fmt(data.score.alpha3, 4));
    s.append('span').text('model: ' + ((ep._meta && ep._meta.model) || rig.agent || '?'));
    s.append('span').text('turns: ' + dialogue.length);
    if (rig.mission_time_s !== undefined) s.append('span').text('mission: ' + fmt(rig.mission_time_s, 1) + ' s');
    s.append('span').text('safety events: ' + events.length);
  }

  // ---- map -----------------------------------------------------------------------------
  var map = null;  // {svg, x, y}
  function worldPoints() {
    var pts = [];
    samples.forEach(function (p) { pts.push([p[1], p[2]]); });
    if (world) {
      (world.geofence || []).forEach(function (p) { pts.push(p); });
      (world.zones || []).forEach(function (z) {
        if (z.polygon.length) z.polygon.forEach(function (p) { pts.push(p); });
        else { pts.push([z.centre[0] - z.radius_m, z.centre[1] - z.radius_m]); pts.push([z.centre[0] + z.radius_m, z.centre[1] + z.radius_m]); }
      });
      (world.objectives || []).forEach(function (o) {
        o.area.forEach(function (p) { pts.push(p); });
        if (o.point) { pts.push([o.point[0] - o.radius_m, o.point[1] - o.radius_m]); pts.push([o.point[0] + o.radius_m, o.point[1] + o.radius_m]); }
      });
      (world.peers || []).forEach(function (peer) { peer.path.forEach(function (w) { pts.push([w[1], w[2]]); }); });
      if (world.home) pts.push(world.home);
    }
    if (!pts.length) pts.push([0, 0], [100, 100]);
    return pts;
  }
  function mapScales(size, margin) {
    var pts = worldPoints();
    var x0 = d3.min(pts, function (p) { return p[0]; }), x1 = d3.max(pts, function (p) { return p[0]; });
    var y0 = d3.min(pts, function (p) { return p[1]; }), y1 = d3.max(pts, function (p) { return p[1]; });
    var span = Math.max(x1 - x0, y1 - y0, 10) * 1.06;
    var cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
    return {
      x: d3.scale.linear().domain([cx - span / 2, cx + span / 2]).range([margin, size - margin]),
      y: d3.scale.linear().domain([cy - span / 2, cy + span / 2]).range([size - margin, margin])
    };
  }
  function polygonPath(points, m) {
    return 'M' + points.map(function (p) { return m.x(p[0]) + ',' + m.y(p[1]); }).join('L') + 'Z';
  }
  function drawWorld(g, m) {
    if (!world) return;
    if (world.geofence && world.geofence.length >= 3) g.append('path').attr('class', 'geofence').attr('d', polygonPath(world.geofence, m));
    (world.objectives || []).forEach(function (o) {
      if (o.area.length >= 3) g.append('path').attr('class', 'objective-area').attr('d', polygonPath(o.area, m));
      else if (o.point) g.append('circle').attr('class', 'objective-point').attr('cx', m.x(o.point[0])).attr('cy', m.y(o.point[1]))
        .attr('r', Math.max(4, m.x(o.point[0] + o.radius_m) - m.x(o.point[0])));
      var at = o.area.length ? d3.geom.polygon(o.area.slice()).centroid() : o.point;
      if (at) g.append('text').attr('class', 'objective-label').attr('x', m.x(at[0]) + 6).attr('y', m.y(at[1]) - 6).text(o.id + ' (' + o.type + ')');
    });
    (world.zones || []).forEach(function (z) {
      var at;
      if (z.polygon.length >= 3) {
        g.append('path').attr('class', 'zone').attr('d', polygonPath(z.polygon, m));
        at = d3.geom.polygon(z.polygon.slice()).centroid();
      } else {
        g.append('circle').attr('class', 'zone').attr('cx', m.x(z.centre[0])).attr('cy', m.y(z.centre[1]))
          .attr('r', m.x(z.centre[0] + z.radius_m) - m.x(z.centre[0]));
        at = z.centre;
      }
      var floor = z.floor_m === null ? 'ground' : fmt(z.floor_m, 0) + ' m';
      var ceiling = z.ceiling_m === null ? 'no ceiling' : fmt(z.ceiling_m, 0) + ' m';
      g.append('text').attr('class', 'zone-label').attr('x', m.x(at[0])).attr('y', m.y(at[1])).text(z.id + ' ' + floor + '–' + ceiling);
    });
    (world.peers || []).forEach(function (peer) {
      var line = d3.svg.line().x(function (w) { return m.x(w[1]); }).y(function (w) { return m.y(w[2]); });
      g.append('path').attr('class', 'peer-plan').attr('d', line(peer.path));
      peer.path.forEach(function (w) {
        g.append('text').attr('class', 'peer-label').attr('x', m.x(w[1]) + 4).attr('y', m.y(w[2]) + 12).text(peer.id + ' t=' + fmt(w[0], 0) + ' s');
      });
    });
    if (world.home) g.append('rect').attr('class', 'home').attr('x', m.x(world.home[0]) - 5).attr('y', m.y(world.home[1]) - 5)
      .attr('width', 10).attr('height', 10).append('title').text('home');
  }
  // One path per agent turn: the samples from its start to the next agent turn's start.
  function drawTrack(g, m) {
    var agentTurns = agentTurnIndices();
    var line = d3.svg.line().x(function (p) { return m.x(p[1]); }).y(function (p) { return m.y(p[2]); });
    agentTurns.forEach(function (i, k) {
      var from = turnSpan(i).start;
      var to = k + 1 < agentTurns.length ? turnSpan(agentTurns[k + 1]).start : Infinity;
      if (k === 0) from = -Infinity;
      var seg = samples.filter(function (p) { return p[0] >= from && p[0] <= to; });
      var next = samples.filter(function (p) { return p[0] > to; })[0];
      if (next) seg.push(next);
      g.append('path').attr('class', 'track-seg').attr('data-turn', dialogue[i].turn)
        .style('stroke', turnColour(k % 10)).attr('d', seg.length ? line(seg) : null)
        .append('title').text('agent turn ' + dialogue[i].turn + ': ' + (dialogue[i].intent || ''));
    });
  }
  function drawEvents(g, m) {
    var symbol = d3.svg.symbol().type('triangle-up').size(90);
    events.forEach(function (e) {
      g.append('path').attr('class', 'event-marker').attr('data-kind', e.kind).attr('d', symbol)
        .attr('transform', 'translate(' + m.x(e.p_W_m[0]) + ',' + m.y(e.p_W_m[1]) + ')')
        .style('fill', eventColour(e.kind))
        .append('title').text(e.kind + ' at ' + fmt(e.t_s, 1) + ' s: ' + (e.detail || ''));
    });
  }
  // A swatch and its label; the label is text, never markup (it may be an episode's event kind).
  function legendEntry(legend, colour, opacity, label) {
    var entry = legend.append('span');
    entry.append('i').style('background', colour).style('opacity', opacity);
    entry.node().appendChild(document.createTextNode(label));
  }
  function drawMapLegend() {
    var legend = d3.select('#map-legend');
    var kinds = d3.set(events.map(function (e) { return e.kind; })).values();
    kinds.forEach(function (k) { legendEntry(legend, eventColour(k), 1, k); });
    legendEntry(legend, '#d62728', 0.5, 'no-fly zone');
    legendEntry(legend, '#9467bd', 1, 'peer (plan)');
    legendEntry(legend, '#2ca02c', 1, 'objective');
    legend.append('span').text('track: one colour per agent turn');
  }
  function drawMap() {
    var size = 640, margin = 48;
    var m = mapScales(size, margin);
    var svg = d3.select('#map').append('svg').attr('width', size).attr('height', size).attr('id', 'map-svg');
    svg.append('g').attr('class', 'axis').attr('transform', 'translate(0,' + (size - margin) + ')').call(d3.svg.axis().scale(m.x).ticks(6));
    svg.append('g').attr('class', 'axis').attr('transform', 'translate(' + margin + ',0)').call(d3.svg.axis().scale(m.y).orient('left').ticks(6));
    var g = svg.append('g');
    drawWorld(g, m);
    drawTrack(g, m);
    drawEvents(g, m);
    if (!samples.length && ep.initial_state && ep.initial_state.uav && ep.initial_state.uav.pose) {
      var p = ep.initial_state.uav.pose;
      g.append('circle').attr('class', 'vehicle').attr('r', 5).attr('cx', m.x(p.x)).attr('cy', m.y(p.y)).append('title').text('start (no trajectory in a corpus episode)');
    }
    var vehicle = g.append('circle').attr('class', 'vehicle').attr('id', 'vehicle').attr('r', 6).style('display', samples.length ? null : 'none');
    map = { svg: svg, x: m.x, y: m.y, vehicle: vehicle };
    drawMapLegend();
  }

  // ---- timelines -----------------------------------------------------------------------
  var timelines = [];  // {x, cursor}
  var width = 560, lm = 56, rm = 12;
  var x = d3.scale.linear().domain([0, T]).range([lm, width - rm]);
  function timeline(name, height, yDomain, yLabel) {
    var svg = d3.select('#timelines').append('svg').attr('class', 'timeline').attr('data-name', name).attr('width', width).attr('height', height);
    var y = d3.scale.linear().domain(yDomain).nice().range([height - 20, 18]);
    svg.append('g').attr('class', 'axis').attr('transform', 'translate(0,' + (height - 20) + ')').call(d3.svg.axis().scale(x).ticks(8));
    if (name !== 'turns') svg.append('g').attr('class', 'axis').attr('transform', 'translate(' + lm + ',0)').call(d3.svg.axis().scale(y).orient('left').ticks(4));
    svg.append('text').attr('x', lm + 4).attr('y', 11).text(yLabel);
    var cursor = svg.append('line').attr('class', 'cursor').attr('y1', 4).attr('y2', height - 20);
    svg.on('mousemove', function () { setTime(x.invert(d3.mouse(this)[0])); });
    timelines.push({ cursor: cursor });
    return { svg: svg, y: y };
  }
  function series(tl, points, colour) {
    var line = d3.svg.line().x(function (p) { return x(p[0]); }).y(function (p) { return tl.y(p[1]); });
    tl.svg.append('path').attr('class', 'series').style('stroke', colour).attr('d', line(points));
  }
  function stepSeries(tl, points, colour) {
    var line = d3.svg.line().interpolate('step-after').x(function (p) { return x(p[0]); }).y(function (p) { return tl.y(p[1]); });
    tl.svg.append('path').attr('class', 'series').style('stroke', colour).attr('d', line(points));
  }
  function column(c) { return samples.map(function (p) { return [p[0], p[c]]; }); }
  function drawFlightTimelines() {
    if (!samples.length) return;
    var bounds = (world && world.alt_bounds) || null;
    var zMax = d3.max(samples, function (p) { return p[3]; });
    var alt = timeline('altitude', 130, [Math.min(0, bounds ? bounds[0] : 0), Math.max(zMax, bounds && isFinite(bounds[1]) && bounds[1] < 4 * zMax ? bounds[1] : zMax) * 1.05 + 1], 'altitude m');
    series(alt, column(3), '#1f77b4');
    if (bounds) bounds.forEach(function (b) {
      if (b !== null && b >= alt.y.domain()[0] && b <= alt.y.domain()[1]) alt.svg.append('line').attr('class', 'bound').attr('x1', x(0)).attr('x2', x(T)).attr('y1', alt.y(b)).attr('y2', alt.y(b));
    });
    series(timeline('speed', 100, [0, d3.max(samples, function (p) { return p[5]; }) + 1], 'speed m/s'), column(5), '#2ca02c');
    series(timeline('battery', 100, [0, 100], 'battery %'), column(4), '#8c564b');
  }
  function netPoints(field) {
    var out = [];
    dialogue.forEach(function (turn, i) {
      if (turn.net && typeof turn.net[field] === 'number') out.push([turnSpan(i).start, turn.net[field]]);
    });
    if (out.length) out.push([T, out[out.length - 1][1]]);
    return out;
  }
  function drawDegradations(tl) {
    ((world && world.degradations) || []).forEach(function (w) {
      tl.svg.insert('rect', ':first-child').attr('class', 'degradation').attr('x', x(w[0])).attr('width', Math.max(1, x(w[0] + w[1]) - x(w[0])))
        .attr('y', 4).attr('height', tl.y.range()[0] - 4).append('title').text('forced degradation');
    });
  }
  function drawSliceBands(tl) {
    var colours = { URLLC: '#17becf', eMBB: '#bcbd22', mMTC: '#7f7f7f' };
    dialogue.forEach(function (turn, i) {
      if (!turn.net || !turn.net.slice) return;
      var s = turnSpan(i), e = i + 1 < dialogue.length ? turnSpan(i + 1).start : T;
      tl.svg.insert('rect', ':first-child').attr('x', x(s.start)).attr('width', Math.max(1, x(e) - x(s.start))).attr('y', 4).attr('height', 6)
        .style('fill', colours[turn.net.slice] || '#ccc').append('title').text(turn.net.slice);
    });
  }
  function drawLinkTimelines() {
    var fields = [['lat_ms', 'latency ms', '#d62728'], ['loss_pct', 'loss %', '#9467bd'], ['throughput_mbps', 'throughput Mbit/s', '#17becf'], ['edge_load', 'edge load', '#ff7f0e']];
    fields.forEach(function (f) {
      var pts = netPoints(f[0]);
      if (!pts.length) return;
      var tl = timeline('net-' + f[0], 90, [0, d3.max(pts, function (p) { return p[1]; }) * 1.1 || 1], f[1] + ' (slice band on top)');
      drawSliceBands(tl);
      drawDegradations(tl);
      stepSeries(tl, pts, f[2]);
    });
  }
  // Each turn as a bar: its span, the agent's think time, and its messages' time on the link.
  function drawTurnTimeline() {
    if (!dialogue.length) return;
    var tl = timeline('turns', 120, [0, 2], 'turns (think ▮, link ▮)');
    var y = function (speaker) { return speaker === 'agent' ? 20 : 58; };
    tl.svg.append('text').attr('x', 4).attr('y', 40).text('agent');
    tl.svg.append('text').attr('x', 4).attr('y', 78).text('supervisor');
    dialogue.forEach(function (turn, i) {
      var s = turnSpan(i), colour = turn.speaker === 'agent' ? '#1f77b4' : '#7f7f7f';
      var g = tl.svg.append('g').attr('class', 'turn-bar').attr('data-turn', turn.turn);
      g.append('rect').attr('class', 'turn-span').attr('x', x(s.start)).attr('width', Math.max(1, x(s.end) - x(s.start))).attr('y', y(turn.speaker)).attr('height', 30).style('fill', colour);
      if (timed && s.decided > s.start) g.append('rect').attr('class', 'turn-think').attr('x', x(s.start)).attr('width', Math.max(1, x(s.decided) - x(s.start))).attr('y', y(turn.speaker)).attr('height', 14).style('fill', colour);
      if (timed && s.delivered > s.sent) g.append('rect').attr('class', 'turn-link').attr('x', x(s.sent)).attr('width', Math.max(1, x(s.delivered) - x(s.sent))).attr('y', y(turn.speaker) + 16).attr('height', 14);
      var r = rigTurns[i] || {};
      g.append('title').text('turn ' + turn.turn + ' (' + turn.speaker + ') ' + (turn.intent || '') +
        (timed ? '\nthink ' + fmt(r.think_time_s, 2) + ' s, link ' + fmt((r.delivered_s - r.sent_s) * 1000, 1) + ' ms' : ''));
    });
  }
  function drawTimelines() {
    drawFlightTimelines();
    drawLinkTimelines();
    drawTurnTimeline();
    d3.select('#timelines').append('div').attr('class', 'legend').text('horizontal axis: ' + (timeUnit === 's' ? 'mission time, s' : 'turn number'));
  }

  // ---- score and dialogue --------------------------------------------------------------
  // Every value goes into the page as text (d3's .text), never as markup.
  function tableRow(table, cellTag, values) {
    var tr = table.append('tr');
    values.forEach(function (v) { tr.append(cellTag).text(v); });
    return tr;
  }
  function drawScore() {
    var s = data.score || {};
    var el = d3.select('#score');
    if (!s.valid) {
      el.append('p').text('not a valid α³-Bench episode (α³ = 0): ' + (s.violations || []).join('; '));
      return;
    }
    var rows = [['α³', s.alpha3, 'the composite'], ['TO', s.pillars.TO, 'task outcome'], ['SP', s.pillars.SP, 'safety policy'],
      ['TC', s.pillars.TC, 'tool consistency'], ['IQ', s.pillars.IQ, 'interaction quality'], ['NR', s.pillars.NR, 'network robustness'], ['CC', s.pillars.CC, 'communication cost']];
    var table = el.append('table').attr('id', 'score-table');
    tableRow(table, 'th', ['pillar', 'score', 'what']);
    rows.forEach(function (r) { tableRow(table, 'td', [r[0], fmt(r[1], 4), r[2]]); });
    el.append('p').text('computed from: ' + Object.keys(s.inputs).map(function (k) { return k + ' = ' + JSON.stringify(s.inputs[k]); }).join(', '));
  }
  function pre(cell, value) { cell.append('pre').text(value === undefined ? '' : JSON.stringify(value, null, 1)); }
  function drawDialogue() {
    var table = d3.select('#dialogue').append('table').attr('id', 'dialogue-table');
    tableRow(table, 'th', ['turn', 'time', 'speaker / intent', 'text', 'actions', 'observations', 'net']);
    dialogue.forEach(function (turn, i) {
      var tr = table.append('tr').attr('class', 'turn-row').attr('data-index', i);
      var r = rigTurns[i] || {};
      tr.append('td').text(turn.turn);
      tr.append('td').text(timed ? fmt(r.started_s, 1) + ' s' + (turn.speaker === 'agent' ? '\nthink ' + fmt(r.think_time_s, 2) + ' s' : '') : '');
      var who = tr.append('td');
      who.append('div').attr('class', turn.speaker === 'agent' ? 'speaker-agent' : 'speaker-user').text(turn.speaker);
      who.append('div').text(turn.intent || '');
      tr.append('td').text(r.text || turn.text || '');
      pre(tr.append('td'), (turn.actions || []).map(function (a) { return { name: a.name, type: a.type, args: a.args }; }));
      pre(tr.append('td'), turn.obs);
      pre(tr.append('td'), turn.net);
    });
  }

  // ---- scrubbing -----------------------------------------------------------------------
  function positionAt(t) {
    if (!samples.length) return null;
    var i = d3.bisector(function (p) { return p[0]; }).left(samples, t);
    if (i <= 0) return samples[0];
    if (i >= samples.length) return samples[samples.length - 1];
    var a = samples[i - 1], b = samples[i], f = (t - a[0]) / Math.max(1e-9, b[0] - a[0]);
    return [t, a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]), a[3] + f * (b[3] - a[3])];
  }
  var current = -2;
  function setTime(t) {
    t = Math.max(0, Math.min(T, t));
    document.getElementById('time').value = t;
    document.getElementById('time-label').textContent = fmt(t, 1) + ' ' + timeUnit;
    timelines.forEach(function (tl) { tl.cursor.attr('x1', x(t)).attr('x2', x(t)); });
    var p = positionAt(t);
    if (p && map) map.vehicle.attr('cx', map.x(p[1])).attr('cy', map.y(p[2])).select('title').remove();
    if (p && map) map.vehicle.append('title').text('t = ' + fmt(t, 1) + ' s, altitude ' + fmt(p[3], 1) + ' m');
    var turn = turnAt(t);
    if (turn !== current) {
      d3.selectAll('tr.turn-row').classed('current', function () { return +this.getAttribute('data-index') === turn; });
      current = turn;
    }
  }
  function setUpScrub() {
    var input = document.getElementById('time');
    input.max = T;
    input.step = T / 1000;
    input.addEventListener('input', function () { setTime(+input.value); });
    setTime(0);
  }

  // ---- layout facts for tests ----------------------------------------------------------
  function box(el) {
    var r = el.getBoundingClientRect();
    return [Math.round(r.left + window.scrollX), Math.round(r.top + window.scrollY), Math.round(r.width), Math.round(r.height)].join(',');
  }
  function publishFacts() {
    var body = document.body;
    body.setAttribute('data-map-box', box(document.getElementById('map-svg')));
    body.setAttribute('data-timelines-box', box(document.getElementById('timelines')));
    body.setAttribute('data-agent-turns', agentTurnIndices().length);
    body.setAttribute('data-safety-events', events.length);
  }

  drawHeader();
  drawMap();
  drawTimelines();
  drawScore();
  drawDialogue();
  setUpScrub();
  publishFacts();
  document.body.setAttribute('data-drawn', 'yes');
})();

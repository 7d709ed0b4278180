/* arise serve: the page. Plain JavaScript, no build step; every text from the server is
   set with textContent, never parsed as HTML. */
(function () {
  "use strict";

  var FINISHED = { done: true, failed: true, cancelled: true };
  var info = null;
  var current = null; // the job shown on the right: {id, source}
  var runScript = null; // the text of the run shown on the right, for "Drive this script"
  var $ = function (id) { return document.getElementById(id); };

  function el(tag, className, text) {
    var node = document.createElement(tag);
    if (className) { node.className = className; }
    if (text !== undefined && text !== null) { node.textContent = String(text); }
    return node;
  }

  function clear(node) { while (node.firstChild) { node.removeChild(node.firstChild); } }

  async function api(path, options) {
    var response;
    try {
      response = await fetch(path, options);
    } catch (error) {
      throw new Error("the server cannot be reached (" + error.message + ")");
    }
    var body = null;
    try { body = await response.json(); } catch (error) { body = null; }
    if (!response.ok) {
      var message = body && body.error ? body.error : "the server answered " + response.status;
      var failure = new Error(message);
      failure.status = response.status;
      throw failure;
    }
    return body;
  }

  function post(path, data) {
    return api(path, {
      method: "POST",
      headers: { "Content-Type": "application/json" },
      body: JSON.stringify(data)
    });
  }

  function showError(box, error) {
    box.textContent = (error.status ? "(" + error.status + ") " : "") + error.message;
    box.hidden = false;
  }

  // -- the form ---------------------------------------------------------------------
  function fillAgents() {
    Array.prototype.forEach.call(document.querySelectorAll("select.agent-pick"), function (select) {
      (info.agents || []).forEach(function (agent) {
        var option = el("option", null, agent.name + ": " + agent.note);
        option.value = agent.name;
        select.appendChild(option);
      });
    });
    $("drive-agent").value = "idm";
  }

  function fillForm() {
    fillAgents();
    var examples = $("example");
    info.examples.forEach(function (example, index) {
      var option = el("option", null, example.title);
      option.value = String(index);
      examples.appendChild(option);
    });
    var models = $("model");
    info.models.forEach(function (model) {
      var option = el("option", null, model.label + (model.ready ? "" : " (not available)"));
      option.value = model.provider;
      option.disabled = !model.ready;
      models.appendChild(option);
    });
    if (info["default"]) { models.value = info["default"].provider; }
    $("description-limit").textContent = String(info.limits.description_chars);
    modelChanged();
  }

  function chosenModel() {
    var provider = $("model").value;
    return info.models.filter(function (m) { return m.provider === provider; })[0];
  }

  function modelChanged() {
    var model = chosenModel();
    if (!model) { return; }
    $("model-note").textContent = model.note;
    $("model-name").value = model.model;
    $("model-name").disabled = model.provider === "local" || model.provider === "replay";
  }

  function countChars() {
    $("description-count").textContent = String($("description").value.trim().length);
  }

  async function submit(event) {
    event.preventDefault();
    var box = $("form-error");
    box.hidden = true;
    var model = chosenModel();
    try {
      var job = await post("/api/jobs", {
        description: $("description").value,
        provider: model ? model.provider : null,
        model: $("model-name").value || null
      });
      await refreshJobs();
      openJob(job.id);
    } catch (error) {
      showError(box, error);
    }
  }

  // -- the job list -----------------------------------------------------------------
  function stateBadge(node, state) {
    node.textContent = state;
    node.className = "badge " + state;
  }

  async function refreshJobs() {
    var data;
    try { data = await api("/api/jobs"); } catch (error) { return; }
    var list = $("jobs");
    clear(list);
    data.jobs.forEach(function (job) {
      var item = el("li", "job");
      item.dataset.id = job.id;
      item.dataset.state = job.state;
      if (current && current.id === job.id) { item.classList.add("selected"); }
      var badge = el("span");
      stateBadge(badge, job.state);
      item.appendChild(badge);
      var where = job.position ? " (#" + job.position + " in line)" : "";
      item.appendChild(el("span", "job-text", job.description + where));
      item.appendChild(el("span", "job-model", job.key));
      if (!FINISHED[job.state]) {
        var button = el("button", "job-cancel", "Cancel");
        button.type = "button";
        button.addEventListener("click", function (e) { e.stopPropagation(); cancel(job.id); });
        item.appendChild(button);
      }
      item.addEventListener("click", function () { openJob(job.id); });
      list.appendChild(item);
    });
    var queue = data.queue.filter(function (q) { return q.running || q.waiting; });
    $("queue").textContent = queue.length === 0 ? "No job is running." : queue.map(function (q) {
      return q.key + ": " + (q.running ? "1 running" : "idle") + ", " + q.waiting + " waiting";
    }).join(" · ");
    if (current) {
      var mine = data.jobs.filter(function (j) { return j.id === current.id; })[0];
      if (mine) { showJobHead(mine); }
    }
  }

  async function cancel(id) {
    try {
      await post("/api/jobs/" + encodeURIComponent(id) + "/cancel", {});
    } catch (error) {
      showError($("form-error"), error);
    }
    refreshJobs();
  }

  // -- one job ----------------------------------------------------------------------
  function showJobHead(job) {
    $("run-title").textContent = job.description;
    stateBadge($("run-state"), job.state);
    var where = job.position ? "Waiting: #" + job.position + " in line for " + job.key + ". " : "";
    $("run-message").textContent = where + (job.message || "");
    $("cancel").hidden = !!FINISHED[job.state];
  }

  function stageText(event) {
    if (event.event === "stage") {
      var text = event.stage + (event.attempt !== undefined ? " (attempt " + event.attempt + ")" : "");
      return event.error ? text + ": " + event.error : text;
    }
    if (event.event === "attempt") {
      var head = "attempt " + event.index + " (" + event.kind + (event.detail ? ", " + event.detail : "") + ")";
      return head + (event.ok ? ": ran" : ": failed" + (event.error ? ": " + event.error : ""));
    }
    if (event.event === "done") { return "finished: " + event.summary; }
    if (event.event === "state") { return "job " + event.state + (event.message ? ": " + event.message : ""); }
    return JSON.stringify(event);
  }

  function addStage(event) {
    var item = el("li", "stage " + event.event, stageText(event));
    item.dataset.event = event.event;
    if (event.stage) { item.dataset.stage = event.stage; }
    if (event.event === "attempt") { item.classList.add(event.ok ? "ok" : "bad"); }
    if (event.event === "state") { item.dataset.state = event.state; }
    $("stages").appendChild(item);
  }

  function openJob(id) {
    if (current && current.source) { current.source.close(); }
    current = { id: id, source: null };
    $("empty").hidden = true;
    $("check-result").hidden = true;
    $("run").hidden = false;
    $("result").hidden = true;
    clear($("stages"));
    Array.prototype.forEach.call(document.querySelectorAll("#jobs li"), function (li) {
      li.classList.toggle("selected", li.dataset.id === id);
    });
    api("/api/jobs/" + encodeURIComponent(id)).then(showJobHead).catch(function () {});
    var source = new EventSource("/api/jobs/" + encodeURIComponent(id) + "/events");
    current.source = source;
    ["stage", "attempt", "done", "state"].forEach(function (name) {
      source.addEventListener(name, function (message) {
        if (!current || current.id !== id) { return; }
        var event = JSON.parse(message.data);
        addStage(event);
        if (event.event === "state") {
          refreshJobs();
          if (FINISHED[event.state]) { source.close(); showRun(id); }
        }
      });
    });
    source.onerror = function () {
      // The stream ends when the job has ended; the run view says the rest.
      source.close();
      api("/api/jobs/" + encodeURIComponent(id)).then(function (job) {
        if (FINISHED[job.state] && current && current.id === id) { showRun(id); }
      }).catch(function () {});
    };
  }

  // -- a finished run -----------------------------------------------------------------
  async function showRun(id) {
    var view;
    try { view = await api("/api/runs/" + encodeURIComponent(id)); } catch (error) { return; }
    if (!current || current.id !== id) { return; }
    showJobHead(view.job);
    var base = "/runs/" + encodeURIComponent(id);
    $("result").hidden = false;
    var zip = $("download-zip");
    zip.href = base + "/download.zip";
    zip.hidden = view.files.length === 0;
    var links = $("file-links");
    clear(links);
    view.files.concat(view.viewable.filter(function (n) { return n !== "replay.html"; })).forEach(function (name) {
      var link = el("a", null, name);
      link.href = base + "/files/" + encodeURIComponent(name);
      link.target = "_blank";
      link.rel = "noopener";
      links.appendChild(link);
    });
    (view.skipped || []).forEach(function (note) {  // links and special files: not served
      links.appendChild(el("span", "hint", "skipped " + note));
    });
    var hasReplay = view.viewable.indexOf("replay.html") >= 0;
    var frame = $("replay");
    frame.hidden = !hasReplay;
    $("no-replay").hidden = hasReplay;
    frame.src = hasReplay ? base + "/files/replay.html" : "about:blank";
    showScript(view.script);
    runScript = view.script && !view.script.failed ?
      view.script.lines.map(function (line) { return line.text; }).join("\n") + "\n" : null;
    $("drive-form").hidden = !(hasReplay && runScript);
    $("drive-error").hidden = true;
    showAttempts(view.attempts || []);
    showSpec(view.spec);
    showConformity(view.conformity, view.report);
  }

  function showScript(script) {
    var box = $("script");
    clear(box);
    var legend = $("script-legend");
    if (!script) { legend.textContent = "No script was written."; return; }
    var changed = script.lines.filter(function (l) { return l.attempt > 0; }).length;
    legend.textContent = script.sections.length + " sections; " +
      (changed ? changed + " line(s) changed by repairs (marked with the attempt that wrote them)" : "no line changed by a repair") +
      (script.failed ? "; this script did NOT execute" : "");
    script.lines.forEach(function (line) {
      var row = el("span", "line" + (line.attempt > 0 ? " changed" : ""));
      row.dataset.line = String(line.number);
      if (line.section) { row.dataset.section = line.section; }
      row.appendChild(el("span", "number", line.number));
      row.appendChild(el("span", "section", line.section || ""));
      row.appendChild(el("span", "origin", line.attempt > 0 ? "#" + line.attempt + " " + (line.kind || "") : ""));
      row.appendChild(el("span", "text", line.text));
      box.appendChild(row);
    });
  }

  function showAttempts(attempts) {
    var list = $("attempts");
    clear(list);
    attempts.forEach(function (a) {
      var item = el("li", a.executed ? "ok" : "bad");
      var head = "#" + a.index + " " + a.kind + (a.detail ? " (" + a.detail + ")" : "") + ": " +
        (a.ok ? "ran" : a.executed ? "ran, but contradicts the description" : "failed") + ", " + a.seconds + " s";
      item.appendChild(el("div", "attempt-head", head));
      if (a.diagnostic) { item.appendChild(el("div", "diagnostic", a.diagnostic)); }
      if (a.hint) { item.appendChild(el("div", "hint", "hint: " + a.hint)); }
      a.contradictions.forEach(function (c) {
        item.appendChild(el("div", "diagnostic", c.check + ": expected " + c.expected + ", observed " + c.observed));
      });
      if (a.diff) {
        var details = el("details");
        details.appendChild(el("summary", null, "what this attempt changed"));
        details.appendChild(el("pre", "code", a.diff));
        item.appendChild(details);
      }
      list.appendChild(item);
    });
  }

  function showSpec(spec) {
    var body = $("facts").querySelector("tbody");
    clear(body);
    var notes = $("spec-notes");
    clear(notes);
    if (!spec) { notes.appendChild(el("li", null, "No spec: the description was refused or the model failed.")); return; }
    spec.facts.forEach(function (fact) {
      var row = el("tr", "fact " + fact.source);
      row.appendChild(el("td", null, fact.name));
      row.appendChild(el("td", null, fact.value));
      row.appendChild(el("td", null, fact.source === "default" ? "not stated" : fact.source));
      row.appendChild(el("td", "quote", fact.quote ? "\u201c" + fact.quote + "\u201d" : ""));
      body.appendChild(row);
    });
    spec.actors.forEach(function (text) { notes.appendChild(el("li", null, text)); });
    spec.corrections.forEach(function (text) { notes.appendChild(el("li", null, text)); });
    spec.contradictions.forEach(function (text) { notes.appendChild(el("li", "bad", "contradiction: " + text)); });
    spec.ignored.forEach(function (text) { notes.appendChild(el("li", null, "left out: " + text)); });
  }

  function showConformity(conformity, report) {
    var body = $("conformity").querySelector("tbody");
    clear(body);
    var gate = report && report.semantic_gate;
    $("gate").textContent = gate ? "semantic gate: " + gate.verdict +
      (gate.contradictions.length ? " (" + gate.contradictions.length + " contradiction(s) left)" : "") : "";
    if (!conformity) { return; }
    conformity.checks.forEach(function (check) {
      var row = el("tr", check.ok === true ? "ok" : check.ok === false ? "bad" : "unknown");
      row.appendChild(el("td", null, check.name));
      row.appendChild(el("td", null, check.expected));
      row.appendChild(el("td", null, check.observed));
      row.appendChild(el("td", null, check.ok === true ? "\u2714" : check.ok === false ? "\u2718" : "?"));
      body.appendChild(row);
    });
  }

  // -- checking a script ----------------------------------------------------------------
  async function checkScript(event) {
    event.preventDefault();
    var box = $("check-error");
    box.hidden = true;
    var file = $("script-file").files[0];
    var name = file ? file.name : null;
    var button = $("check");
    try {
      if (file && file.size > info.limits.script_bytes) {
        throw new Error("the file is " + Math.ceil(file.size / 1024) + " KiB; the limit is " +
          Math.floor(info.limits.script_bytes / 1024) + " KiB");
      }
      var text = file ? await file.text() : $("script-text").value;
      button.disabled = true;
      button.textContent = "Checking\u2026";
      var agent = $("check-agent").value || null;
      var result = await post("/api/check", { script: text, name: name, agent: agent });
      showCheck(result);
    } catch (error) {
      showError(box, error);
    } finally {
      button.disabled = false;
      button.textContent = "Check in the validator";
    }
  }

  async function driveRun(event) {
    event.preventDefault();
    var box = $("drive-error");
    box.hidden = true;
    if (!runScript || !current) { return; }
    var button = $("drive");
    var name = "job " + current.id;
    try {
      button.disabled = true;
      button.textContent = "Driving\u2026";
      showCheck(await post("/api/check", { script: runScript, name: name, agent: $("drive-agent").value }));
    } catch (error) {
      showError(box, error);
    } finally {
      button.disabled = false;
      button.textContent = "Drive";
    }
  }

  function showDriving(result) {
    var driving = result.driving;
    var box = $("check-driving");
    box.hidden = !driving;
    if (!driving) { return; }
    $("check-driving-agent").textContent = driving.agent;
    var verdict = $("check-driving-verdict");
    verdict.hidden = !!driving.error;
    verdict.textContent = driving.collision ? "collision" : "no collision";
    verdict.className = "badge " + (driving.collision ? "failed" : "done");
    var body = $("check-metrics").tBodies[0];
    clear(body);
    driving.metrics.forEach(function (metric) {
      var row = el("tr");
      row.dataset.metric = metric.metric;
      row.appendChild(el("td", null, metric.label));
      var value = metric.value === null || metric.value === undefined ? "-" :
        (Number.isInteger(metric.value) ? String(metric.value) : Number(metric.value).toFixed(2));
      row.appendChild(el("td", "value", value));
      row.appendChild(el("td", "hint", metric.meaning));
      body.appendChild(row);
    });
    $("check-driving-note").textContent = driving.error ||
      "One run, seed 0: the mean over many runs is `arise drive` (docs/agents.md has each definition).";
  }

  function showCheck(result) {
    if (current && current.source) { current.source.close(); }
    current = null;
    $("empty").hidden = true;
    $("run").hidden = true;
    $("check-result").hidden = false;
    var verdict = $("check-verdict");
    verdict.textContent = result.ok ? "runs" : "fails";
    verdict.className = "badge " + (result.ok ? "done" : "failed");
    $("check-summary").textContent = (result.name ? result.name + ": " : "") + result.summary +
      (result.map ? " · map " + result.map + (result.map_note ? " (" + result.map_note + ")" : "") : "");
    var d = result.diagnostic;
    $("check-diagnostic").hidden = !d;
    $("check-excerpt").textContent = d ? (d.excerpt || result.diagnostic_line) : "";
    $("check-hint").textContent = d && d.hint ? "hint: " + d.hint : "";
    $("check-sandbox").textContent = "sandbox: " + (result.sandbox || "none (the script never reached a worker)") +
      (result.warnings.length ? " · " + result.warnings.join(" · ") : "");
    var frame = $("check-replay");
    frame.hidden = !result.replay;
    frame.src = result.replay ? "/checks/" + encodeURIComponent(result.id) + "/files/" + result.replay : "about:blank";
    showDriving(result);
  }

  // -- start ----------------------------------------------------------------------------
  async function start() {
    try {
      info = await api("/api/info");
    } catch (error) {
      showError($("form-error"), error);
      return;
    }
    fillForm();
    $("example").addEventListener("change", function () {
      var chosen = info.examples[parseInt($("example").value, 10)];
      if (chosen) { $("description").value = chosen.description; countChars(); }
    });
    $("model").addEventListener("change", modelChanged);
    $("description").addEventListener("input", countChars);
    $("generate-form").addEventListener("submit", submit);
    $("check-form").addEventListener("submit", checkScript);
    $("drive-form").addEventListener("submit", driveRun);
    $("cancel").addEventListener("click", function () { if (current) { cancel(current.id); } });
    await refreshJobs();
    setInterval(function () { if (!document.hidden) { refreshJobs(); } }, 2000);
    var wanted = new URLSearchParams(location.search).get("job");
    if (wanted) { openJob(wanted); }
  }

  document.addEventListener("DOMContentLoaded", start);
}());

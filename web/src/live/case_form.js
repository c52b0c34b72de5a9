// "Run a bundled case" (#live-case): the server's bundled cases in #case-select, the chosen case's
// spec as JSON in #case-spec with its duration and friction as two quick fields, and Submit, which
// queues the spec as a job and calls onSubmitted(job).

import * as server from './server.js';
import { formatSpec } from './spec_format.js';
import { errorText } from './session.js';

// Every interaction of the spec: its own, and those its stages set from their start on (a staged
// case's load stage sets the frictions the loading runs with).
function interactionsOf(spec) {
  return [...(spec.interactions || []), ...(spec.stages || []).flatMap((stage) => stage.interactions || [])];
}

// A case description's markdown links as their text.
function plain(markdown) {
  return (markdown || '').replace(/\[`?([^\]`]+)`?\]\([^)]*\)/g, '$1');
}

export class CaseForm {
  constructor(say, onSubmitted) {
    this.say = say; // (text, isError): a message where the user looks
    this.onSubmitted = onSubmitted;
    this.cases = [];
    this.caseSpecs = new Map(); // name -> promise of its spec (asked once)
    this.select = document.getElementById('case-select');
    this.description = document.getElementById('case-description');
    this.duration = document.getElementById('case-duration');
    this.friction = document.getElementById('case-friction');
    this.specText = document.getElementById('case-spec');
    this.submitButton = document.getElementById('submit-case');
    this.select.addEventListener('change', () => this.loadCase(this.select.value));
    this.duration.addEventListener('input', () => this.quickEdit('duration'));
    this.friction.addEventListener('input', () => this.quickEdit('friction'));
    this.specText.addEventListener('input', () => this.specEdited());
    this.submitButton.addEventListener('click', () => this.submit());
  }

  disable() {
    this.select.disabled = true;
  }

  async loadCases() {
    try {
      this.cases = await server.listCases();
    } catch (e) {
      this.description.textContent = `Bundled cases: ${errorText(e)}`;
      return;
    }
    this.select.textContent = '';
    for (const c of this.cases) {
      const option = document.createElement('option');
      option.value = c.name;
      option.textContent = c.title || c.name;
      if (c.description) option.title = c.description;
      this.select.appendChild(option);
    }
    if (!this.cases.length) {
      this.description.textContent = 'The server has no bundled cases.';
      return;
    }
    await this.loadCase(this.select.value || this.cases[0].name);
  }

  async caseSpec(name) {
    if (!this.caseSpecs.has(name)) this.caseSpecs.set(name, server.getCase(name));
    try {
      return await this.caseSpecs.get(name);
    } catch (e) {
      this.caseSpecs.delete(name);
      throw e;
    }
  }

  async loadCase(name) {
    const c = this.cases.find((k) => k.name === name);
    this.description.textContent = c ? plain(c.description) : '';
    this.description.title = this.description.textContent;
    this.submitButton.disabled = true;
    try {
      const spec = await this.caseSpec(name);
      if (this.select.value !== name) return; // another case was chosen meanwhile
      this.setSpec(structuredClone(spec));
    } catch (e) {
      this.say(`bundled case ${name}: ${errorText(e)}`, true);
    }
  }

  setSpec(spec) {
    this.specText.value = formatSpec(spec);
    this.specText.classList.remove('error');
    this.fillQuickFields(spec);
    this.submitButton.disabled = false;
  }

  fillQuickFields(spec) {
    // a staged run lasts as long as its stages: the server refuses a duration beside them
    const staged = Array.isArray(spec.stages) && spec.stages.length > 0;
    this.duration.disabled = staged;
    this.duration.title = staged ? 'a staged case lasts as long as its stages: set each stage\'s duration in the spec' : 'time.duration of the spec, s';
    const duration = spec.time ? Number(spec.time.duration) : NaN;
    this.duration.value = !staged && Number.isFinite(duration) && duration > 0 ? String(duration) : '';
    this.duration.placeholder = staged ? 'stages' : spec.time && spec.time.steps ? `${spec.time.steps} steps` : '';
    // one value for every pair of materials: shown when they agree, else empty with their range
    const frictions = interactionsOf(spec).map((i) => Number(i.friction || 0));
    const distinct = [...new Set(frictions)];
    this.friction.value = distinct.length === 1 ? String(distinct[0]) : '';
    this.friction.placeholder = distinct.length > 1 ? 'varies' : '';
    this.friction.title = distinct.length > 1
      ? `the pairs of materials (and the stages) have frictions ${distinct.join(', ')}: a value here sets every pair's in every stage; or edit each in the spec`
      : 'the friction of every pair of materials, in every stage';
  }

  // The spec in the textarea, or null (and a message when `report`) when it is not a JSON object.
  readSpec(report = true) {
    try {
      const spec = JSON.parse(this.specText.value);
      if (!spec || typeof spec !== 'object' || Array.isArray(spec)) throw new Error('the spec must be a JSON object');
      this.specText.classList.remove('error');
      return spec;
    } catch (e) {
      this.specText.classList.add('error');
      if (report) this.say(`the spec is not valid JSON: ${errorText(e)}`, true);
      return null;
    }
  }

  specEdited() {
    const spec = this.readSpec(false);
    if (spec) this.fillQuickFields(spec);
  }

  // A quick field changed: the spec's duration, or every interaction's friction, set to it.
  quickEdit(which) {
    const input = which === 'duration' ? this.duration : this.friction;
    const value = Number(input.value);
    if (input.value.trim() === '' || !Number.isFinite(value) || value < 0) return;
    const spec = this.readSpec();
    if (!spec) return;
    if (which === 'duration') {
      spec.time = { ...(spec.time || {}) };
      spec.time.duration = value;
      delete spec.time.steps; // give duration or steps, not both
    } else {
      for (const interaction of interactionsOf(spec)) interaction.friction = value;
      this.friction.placeholder = '';
      this.friction.title = 'the friction of every pair of materials, in every stage';
    }
    this.specText.value = formatSpec(spec);
  }

  async submit() {
    const spec = this.readSpec();
    if (!spec) return;
    this.submitButton.disabled = true;
    try {
      const job = await server.submitJob(spec);
      this.say(`job ${job.id} submitted: ${job.particles ?? '?'} particle${job.particles === 1 ? '' : 's'}, ${job.totalSteps ?? '?'} step${job.totalSteps === 1 ? '' : 's'}`);
      await this.onSubmitted(job);
    } catch (e) {
      this.say(errorText(e), true);
    } finally {
      this.submitButton.disabled = false;
    }
  }
}

// The server's jobs in #jobs, newest first: id, name, state, a progress bar. Polled every second;
// a click or Enter on a job calls onOpen(id).

import * as server from './server.js';
import { counted } from '../words.js';
import { ACTIVE, errorText, percent } from './session.js';

function span(parent, className) {
  const el = document.createElement('span');
  el.className = className;
  parent.appendChild(el);
  return el;
}

export class JobList {
  constructor(list, status, onOpen) {
    this.list = list; // #jobs
    this.status = status; // #live-server-status
    this.jobs = new Map(); // id -> job record (last poll)
    this.selectedId = null;
    this.list.addEventListener('click', (e) => {
      const li = e.target.closest('li[data-id]');
      if (li && this.list.contains(li)) onOpen(Number(li.dataset.id));
    });
    this.list.addEventListener('keydown', (e) => {
      const li = e.target.closest('li[data-id]');
      if (li && (e.key === 'Enter' || e.key === ' ')) {
        e.preventDefault();
        onOpen(Number(li.dataset.id));
      }
    });
  }

  // Asks the server for its jobs and shows them; the jobs, or null when the server did not answer.
  async refresh() {
    try {
      const jobs = await server.listJobs();
      this.status.textContent = jobs.length ? '' : 'No jobs yet: submit a bundled case below.';
      this.status.classList.remove('error');
      this.render(jobs);
      return jobs;
    } catch (e) {
      this.status.textContent = `Job list: ${errorText(e)}`;
      this.status.classList.add('error');
      return null;
    }
  }

  select(id) {
    this.selectedId = id;
    for (const li of this.list.querySelectorAll('li[data-id]')) li.classList.toggle('selected', Number(li.dataset.id) === id);
  }

  render(jobs) {
    this.jobs = new Map();
    const seen = new Set();
    let before = this.list.firstChild;
    for (const job of jobs.slice().sort((a, b) => b.id - a.id)) {
      this.jobs.set(job.id, job);
      seen.add(String(job.id));
      let li = this.list.querySelector(`li[data-id="${job.id}"]`);
      if (!li) {
        li = document.createElement('li');
        li.dataset.id = String(job.id);
        li.tabIndex = 0;
        li.className = 'job';
        span(li, 'job-id');
        span(li, 'job-name');
        span(li, 'job-state');
        const bar = document.createElement('progress');
        bar.className = 'job-bar';
        bar.max = 1;
        li.appendChild(bar);
        span(li, 'job-progress');
      }
      if (li !== before) this.list.insertBefore(li, before);
      before = li.nextSibling;
      this.renderJob(li, job);
    }
    for (const li of Array.from(this.list.querySelectorAll('li[data-id]'))) {
      if (!seen.has(li.dataset.id)) li.remove();
    }
  }

  renderJob(li, job) {
    const progress = Number(job.progress) || 0;
    li.dataset.state = job.state;
    li.dataset.progress = String(progress);
    li.classList.toggle('selected', this.selectedId === job.id);
    li.querySelector('.job-id').textContent = `#${job.id}`;
    li.querySelector('.job-name').textContent = ` ${job.name || '(no name)'} `;
    li.querySelector('.job-state').textContent = job.state;
    li.querySelector('.job-bar').value = progress;
    let text = ` ${percent(progress)}`;
    if (job.state === 'running' && Number.isFinite(job.secondsLeft)) text += `, ${Math.round(job.secondsLeft)} s left`;
    li.querySelector('.job-progress').textContent = text;
    const particles = job.particles === undefined || job.particles === null ? '? particles' : counted(job.particles, 'particle');
    const details = [`job ${job.id}: ${job.state}`, `step ${job.step ?? 0} of ${job.totalSteps ?? '?'}`, particles];
    if (job.error) details.push(job.error);
    li.title = `${details.join(', ')}. Click: ${ACTIVE.has(job.state) ? 'follow it live' : 'replay it'}.`;
  }
}

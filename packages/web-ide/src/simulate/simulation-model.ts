/**
 * The Monitor's model of one simulation of the Simulate panel's session (docs/simulation.md "In the
 * IDE"): the answer's steps as the trace records a run writes (stepsToTrace, headed by its
 * `sim_start`), the clock held at the session's time, and the records ended, as a finished run's
 * are: the simulation ran to the session's time and is over (a change of the session simulates it
 * again, into a new model), so the Monitor shows the rows a run's end shows (the flows' closing
 * lines, MonitorModel.recordsEnded), its schemas still active at the end staying active (a
 * simulation's ORD does not end).
 */
import { stepsToTrace, type TraceStep } from '@contract-studio/simulator/trace';
import { MonitorModel } from '../monitor/monitor-model.js';

/** `nowNs`: the session's virtual time (maybe past the last record: nothing happened since). */
export function simulationModel(steps: TraceStep[], nowNs: number): MonitorModel {
  const model = new MonitorModel();
  model.pushAll(stepsToTrace(steps));
  // the session stands at its own time, maybe past its last record: the Monitor's clock says it
  if (model.t0 !== undefined) model.holdUntil(nowNs - model.t0);
  model.recordsEnded();
  return model;
}

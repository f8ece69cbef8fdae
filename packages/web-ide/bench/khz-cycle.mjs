// The records one cycle of a 1 kHz periodic schemaCommande1 writes (ORD's and its three modules'
// MSA -> MSC -> MSD), for the Monitor benchmarks: the live feed (monitor-bench.mjs, in Node) and
// the recorded run it replays (injected into the page). Self-contained: its source is sent to the
// page as it is.
//   L(ns, module, event, peer, port, size, detail)  called for each record, in this order
//   c        the cycle number; state.release counts the releases (ids)
//   full     every record a cycle writes (releases, runs, data posted and received, acks, finished,
//            complete; a deadline miss every 2,000 cycles; a rule change every 500 with the rule it
//            ends): 20 records a cycle. Without: the lean recorded run (releases, runs, data
//            posted, finished; the rule that becomes active every 500 cycles): 14.
export function khzCycle(L, c, state, full) {
  const T0 = 500_000_000_000;
  const mods = ['MSA', 'MSC', 'MSD'];
  const tick = T0 + 10_000_000 + c * 1_000_000;
  let t = tick;
  for (const [i, m] of mods.entries()) {
    const id = ++state.release;
    L(t + 1000, 'ORD', 'ord_release', m, '', 0, `schema=schemaCommande1 cycle=${c} tick_ns=${tick} release_ns=${t + 900} release=${id}`);
    L(t + 5000, m, 'run_started', 'ORD', '', 0, `activation=${id}`);
    if (i < 2) L(t + 40_000, m, 'data_posted', mods[i + 1], i, 24, `to_port=${i === 0 ? 0 : 2}`);
    if (full && i > 0) L(t + 8000, m, 'data_received', mods[i - 1], i === 1 ? 0 : 2, 24, 'latency_ns=9000');
    L(t + 50_000, m, 'run_finished', 'ORD', '', 0, `activation=${id} cpu_ns=41000 ACK_FINISHED`);
    if (full) L(t + 60_000, 'ORD', 'ack_received', m, '', 0, `ACK_FINISHED id=${id}`);
    t += 60_000 + (full ? (c % 97) * 300 : 0);
    L(t + 500, 'ORD', 'ord_finished', m, '', 0, `schema=schemaCommande1 cycle=${c} release=${id} response_ns=${t + 500 - tick}`);
  }
  if (full) {
    L(t + 800, 'ORD', 'ord_complete', '', '', 0, `schema=schemaCommande1 cycle=${c} tick_ns=${tick} response_ns=${t + 800 - tick}`);
    if (c % 2000 === 1999) L(tick + 1_000_000, 'ORD', 'ord_deadline_miss', '', '', 0, `schema=schemaCommande1 cycle=${c} tick_ns=${tick}`);
  }
  if (c % 500 === 0) {
    const on = (c / 500) % 2 === 0;
    L(tick + 2000, 'SUP', 'sup_rule', '', '', 0, `action.${on ? 'SECOND' : 'FIRST'} active cause=elapsed=1000000ns`);
    if (full) L(tick + 2100, 'SUP', 'sup_rule', '', '', 0, `action.${on ? 'FIRST' : 'SECOND'} inactive cause=started(${on ? 'SECOND' : 'FIRST'})`);
  }
}

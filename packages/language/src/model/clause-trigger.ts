/**
 * The event that makes a precondition clause true (docs/semantics.md "Supervisors: occurrences and
 * persistence", "clauses and extractions"): an event without persistence is present only while it
 * is processed, and two such events are never present together. So a clause with one event without
 * persistence is true only while an occurrence of that event is processed; a clause with two or
 * more is never true; a clause whose events all persist may become true on any of them.
 */
import type { Clause, Event } from '../generated/ast.js';

/**
 * `{ event }`: the clause's one event without persistence (the clause is true only while it is
 * processed); `'never'`: it has several (it is never true); `undefined`: every event persists.
 */
export function clauseTrigger(clause: Clause): { event: Event } | 'never' | undefined {
    let found: Event | undefined;
    for (const event of clause.events) {
        if (event.persistence) continue;
        if (found) return 'never';
        found = event;
    }
    return found ? { event: found } : undefined;
}

/**
 * `contract run`'s checks of its options against the project's model, before anything is built:
 * `--start SUP.function(...)` (a misspelt function would leave the run idle) and `--stdin NAME=FILE`
 * (a NAME that is no module left every stdin /dev/null, silently: field test ft69). The model is
 * loaded once, only when one of them is given; one that cannot be read or has errors is not
 * checked here (the build then says what is wrong).
 */
import { closestName } from '@contract-studio/language/near-names';

/** What the checks read of the model. */
export interface RunModel {
    /** supervisor -> its functions, in the model's order */
    supervisors: Map<string, string[]>;
    /** what `make run` starts: ORD, the modules, the supervisors (the architecture Makefile's EXECUTABLES) */
    executables: string[];
    /** the errors of a scenario's `start` line with this text after `start` */
    startArgumentProblems(start: string): Promise<string[]>;
}

/** The project's model in `dir`, or null when it cannot be read or has errors. */
export async function loadRunModel(dir: string): Promise<RunModel | null> {
    try {
        const { loadWorkspace } = await import('@contract-studio/language/node');
        const { isSupervisor } = await import('@contract-studio/language');
        const { architectureOf, architectureExecutables } = await import('@contract-studio/codegen');
        const ws = await loadWorkspace(dir);
        if (ws.diagnostics.some((d) => d.severity === 'error')) return null;
        const supervisors = new Map<string, string[]>();
        for (const d of ws.documents) {
            for (const e of d.model?.elements ?? []) if (isSupervisor(e)) supervisors.set(e.name, e.functions.map((f) => f.name));
        }
        const models = ws.documents.flatMap((d) => (d.model ? [d.model] : []));
        const executables = architectureExecutables(architectureOf(models));
        const startArgumentProblems = async (start: string) => {
            const { parseScenario, checkScenario, indexModels } = await import('@contract-studio/language/scenario');
            const parsed = parseScenario(`start ${start}`);
            if (parsed.diagnostics.length || parsed.steps.length !== 1) return [];
            return checkScenario(parsed.steps, indexModels(models)).diagnostics.filter((d) => d.severity === 'error').map((d) => d.message.replace(/\.$/, ''));
        };
        return { supervisors, executables, startArgumentProblems };
    } catch {
        return null;
    }
}

/**
 * Why `--start SUP.function(...)` names no supervision function of the project's model, or gives
 * it a parameter it does not have or a value of the wrong type, or null (also when the model
 * cannot be read or has errors; and when the arguments are written in a way the scenario reader
 * does not take: the supervisor then reads them itself, and a refusal is a run issue,
 * start-refused). The parameters are checked as a scenario's `start` line is
 * (@contract-studio/language/scenario).
 */
export async function startProblem(start: string, dir: string, model?: RunModel | null): Promise<string | null> {
    const m = /^([A-Za-z_]\w*)\.([A-Za-z_]\w*)/.exec(start);
    if (!m) return null;
    const [, sup, fn] = m as unknown as [string, string, string];
    const loaded = model === undefined ? await loadRunModel(dir) : model;
    if (!loaded) return null;
    const { supervisors } = loaded;
    const all = [...supervisors].flatMap(([s, fns]) => fns.map((f) => `${s}.${f}`));
    const listed = all.length ? `the model's supervision functions: ${all.join(', ')}` : 'the model has no supervision function';
    const functions = supervisors.get(sup);
    if (!functions) {
        const near = closestName(sup, supervisors.keys());
        const guess = near ? ` Did you mean '${near}.${closestName(fn, supervisors.get(near)!) ?? (supervisors.get(near)!.includes(fn) ? fn : supervisors.get(near)![0] ?? fn)}'?` : '';
        return `bad --start '${start}': the model has no supervisor '${sup}'.${guess} (${listed}); nothing was started`;
    }
    if (functions.includes(fn)) {
        const problems = await loaded.startArgumentProblems(start).catch(() => []);
        return problems.length ? `bad --start '${start}': ${problems.slice(0, 5).join('; ')}; nothing was started` : null;
    }
    const near = closestName(fn, functions);
    return `bad --start '${start}': supervisor ${sup} has no function '${fn}'.${near ? ` Did you mean '${sup}.${near}'?` : ''} (${listed}); nothing was started`;
}

/**
 * Why `--stdin NAME=FILE` names no module of the project's model (`bad --stdin MAX=commands.txt:
 * no module 'MAX' in this architecture. Did you mean 'MAA'? (its modules: ORD, MAA, ...); nothing
 * was started`), or null (also when the model cannot be read or has errors).
 */
export async function stdinProblem(stdin: Readonly<Record<string, string>>, model: RunModel | null): Promise<string | null> {
    if (!model) return null;
    const { stdinModulesProblem } = await import('@contract-studio/codegen');
    const problem = stdinModulesProblem(stdin, model.executables, (name, file) => `--stdin ${name}=${file}`);
    return problem ? `bad ${problem}; nothing was started` : null;
}

/**
 * The architecture as the generators see it: plain data with references resolved to names.
 * Built from Langium documents by `from-langium.ts`; tests and benchmarks may build it directly.
 */

export type PrimitiveName = 'int' | 'float' | 'string' | 'bool';

/**
 * A Cactal type: a primitive, a datatype or an enumeration (by name), or (extension) a fixed-size
 * array `float[6]` = `{ array: float, size: 6 }`; `float[3][4]` is an array of 3 `float[4]`.
 */
export type TypeRef = { primitive: PrimitiveName } | { datatype: string } | { enum: string } | { array: TypeRef; size: number };

/** A step of a path: a field name, or an array index (constants folded). */
export type PathSegment = string | number;

/**
 * A value as written in Cactal. `var` is a variable with a path (`temp_message.value`,
 * `scan.ranges[90]`, `ord_schema`). Named constants are replaced by their values; `{...}` is also
 * the value of an array; `enum` is `Mode.AUTO`.
 */
export type Value =
    /** `text`: the integer as written, exact (a number is exact up to 2^53 only); `value` where absent. */
    | { kind: 'int'; value: number; text?: string }
    | { kind: 'real'; value: number }
    | { kind: 'string'; value: string }
    | { kind: 'bool'; value: boolean }
    | { kind: 'enum'; enum: string; member: string }
    | { kind: 'struct'; elements: Value[] }
    | { kind: 'var'; name: string; path: PathSegment[] };

export interface Field {
    name: string;
    type: TypeRef;
    default?: Value;
}

export interface Datatype {
    name: string;
    fields: Field[];
}

/** `enum Mode { IDLE, TELEOP, AUTO }` (extension): members in order, values 0, 1, 2. */
export interface EnumDecl {
    name: string;
    members: string[];
}

/** `const int NJOINTS = 6;` (extension), value folded. */
export interface ConstantDecl {
    name: string;
    type: TypeRef;
    value: Value;
}

export interface FunctionPrototype {
    name: string;
    returns: 'bool' | 'void';
    args: Array<{ name: string; type: TypeRef }>;
}

/** A parameter port or a data/event port of a module or supervisor. */
export interface PortDecl {
    name: string;
    index: number;
    type: TypeRef;
    initial?: Value;
}

export interface Module {
    name: string;
    kind: 'synchronous' | 'asynchronous';
    parameters: PortDecl[];
    dataIn: PortDecl[];
    dataOut: PortDecl[];
    eventIn: PortDecl[];
    eventOut: PortDecl[];
    /** `C` of a synchronous module, in nanoseconds. */
    wcetNs?: number;
}

export interface NamedValue {
    name: string;
    type: TypeRef;
    default?: Value;
}

export interface ParamSetting {
    port: number;
    value: Value;
}

export interface Schema {
    name: string;
    kind: 'periodic' | 'event';
    parameters: NamedValue[];
    periodNs?: number;
    criticalDelayNs?: number;
    modules: Array<{ module: string; settings: ParamSetting[] }>;
    precedences: Array<{ before: string; after: string }>;
    dataFlows: Array<{ source: string; sourcePort: number; target: string; targetPort: number; periodicity: number }>;
    eventFlows: Array<{ source: string; sourcePort: number; target: string; targetPort: number; oneShot: boolean }>;
}

export interface SchedulerConfiguration {
    modules: string[];
    schemas: string[];
}

export type Persistence = undefined | { ns: number } | 'infinite';

export type Test =
    | { op: '==' | '!=' | '<' | '>' | '<=' | '>='; left: Value; right: Value }
    | { op: 'call'; function: string; args: Value[] };

/** `target.path = value` (extractions, notify assignments). */
export interface Assignment {
    target: string;
    path: PathSegment[];
    value: Value;
}

export type Event =
    | { kind: 'started' | 'endof'; rule: string; persistence: Persistence }
    | { kind: 'duration'; rule: string; timeNs: number; persistence: Persistence }
    | { kind: 'elapsed'; timeNs: number; persistence: Persistence }
    /**
     * `source:port`; `inPort`: the supervisor input port whose deliveries it waits for (the
     * language's eventInPort: the only one the function subscribes it to, or the only one of them
     * whose variable it reads), -1 for any of them (and for ORD's events).
     */
    | { kind: 'module'; source: string; port: number; inPort: number; tests: Test[][]; persistence: Persistence; extractions: Assignment[] };

/** `c1 or c2 ...`, each clause `(e1 and e2 ...)`. */
export type Condition = Event[][];

export type Action =
    | { kind: 'schema'; schema: string; assignments: Array<{ parameter: string; value: Value }> }
    | { kind: 'parameterize'; module: string; settings: ParamSetting[] }
    | { kind: 'supervisor'; supervisor: string; function: string; assignments: Array<{ parameter: string; value: Value }> }
    | { kind: 'resttime' | 'critical'; module: string }
    | { kind: 'compute'; function: string; args: Value[] }
    | { kind: 'subscribe'; source: string; sourcePort: number; inPort: number; oneShot: boolean }
    | { kind: 'notify'; port: number; assignments: Assignment[] };

export interface Rule {
    label: string;
    pre: Condition;
    actions: Action[];
    post: Condition;
}

export interface SupervisionFunction {
    name: string;
    parameters: NamedValue[];
    locals: NamedValue[];
    rules: Rule[];
}

export interface Supervisor {
    name: string;
    eventIn: PortDecl[];
    eventOut: PortDecl[];
    functions: SupervisionFunction[];
}

export interface Architecture {
    datatypes: Datatype[];
    /** Extensions; absent means none. */
    enums?: EnumDecl[];
    constants?: ConstantDecl[];
    functions: FunctionPrototype[];
    modules: Module[];
    schemas: Schema[];
    scheduler?: SchedulerConfiguration;
    supervisors: Supervisor[];
}

/**
 * "New project": the report's six template files (datatype, two modules, schema, scheduler
 * configuration, supervisor), small but complete and valid Cactal.
 */
export const PROJECT_TEMPLATES: Record<string, string> = {
  'datatype.contract': `// Data types and function prototypes shared by the whole project.
datatype Position {float x = 0.0, float y = 0.0, float theta = 0.0};
datatype Command {float v = 0.0, float w = 0.0};

function bool isFar(string reason, Position p);
function void trace(string what, float value);
`,
  'module1.contract': `import "datatype.contract";

// Periodic localisation module: publishes the robot position.
synchronous module LOC {
    scheduling { C=500us; }
    data flows { out :0 Position position; }
}
`,
  'module2.contract': `import "datatype.contract";

// Periodic controller: reads the position, produces a velocity command.
synchronous module CTL {
    parameters { Position goal = {1.0, 2.0, 0.0} :0; }
    scheduling { C=1ms; }
    data flows {
        in :0 Position position;
        out :1 Command command;
    }
    event flows { out :0 string status; }
}
`,
  'schema.contract': `import "datatype.contract";
import "module1.contract";
import "module2.contract";

periodic schema goTo(Position goal = {0.0, 0.0, 0.0}) {
    realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; }
    modules { LOC (); CTL (goal:0); }
    scheduling graph { LOC -> CTL; }
    communications { LOC:0 -> CTL:0 * 1; }
}
`,
  'sched.contract': `import "module1.contract";
import "module2.contract";
import "schema.contract";

scheduler configuration {
    modules { LOC; CTL; }
    schemas { goTo; }
}
`,
  'supervisor.contract': `import "datatype.contract";
import "module2.contract";
import "schema.contract";
import "sched.contract";

supervisor MIS {
    event flows { in :0 string status; }
    mission(Position goal = {1.0, 2.0, 0.0}) {
        local { Position target = goal; string last; }
        rules {
            START: [elapsed=1ms]
                subscribe CTL:0 =* :0; activate schema goTo(goal = target)
                [CTL:0(last = status)]
        }
    }
}
`,
};

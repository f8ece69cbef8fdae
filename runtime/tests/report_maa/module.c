/* The report's generated MAA module.c (RR-10026 section 8.2), transcribed unchanged except for
 * the PDF's obvious typos and extraction damage: the missing `{` after
 * `switch(receivedMessage.Param.SetParam.Port)`, the braces of the "3) exiting" branch that the
 * page breaks scrambled, and `message.message_type` -> `message.messagetype` (the field of TypeC
 * in datatype.contract). ACK_NOHING is kept: libmodule.h aliases it. */
//          module source file
//          MODULE: MAA
//          Libraries includes
#include <libmodule/libmodule.h>
#include <stdio.h>
#include <time.h>
#include <string.h>
#include "tools.h"
#include "SharedTypeC.h"
#include "SharedTypeE.h"
#include "SharedTypeA.h"

//from here you can make new imports or definitions

/*PROTECTED REGION ID(protect_additionnal_import_MAA) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

MODULE_DESCRIPTION(/*PROTECTED REGION ID(protect_description_MAA) ENABLED START*/"test asynchronous module A for Cactal generation testing"/*PROTECTED REGION END*/);
MODULE_AUTHOR(/*PROTECTED REGION ID(protect_author_MAA) ENABLED START*/"Robin Passama"/*PROTECTED REGION END*/);

//Exchanges Management Variables
char controlevent[256] = "\0";
TypeC message_type_notification = { "\0", 0, { 0.0, 0.0, 0.0 } };
TypeE received_message = { { "\0", 0, { 0.0, 0.0, 0.0 } }, { "\0", 0 } };
char connection_status[256] = "\0";
TypeA param = {22.12, 6.98, 897.34};

// module name
char MODULE_NAME[] = "MAA";
//module priority
int MODULE_PRIORITY = 37;
// input data flows : example = { &Variable, PortReception, Taille, Periodicity (important if module name is set), "Name of emitter module"(can be unused by setting value to "---"), PortModuleEmetteur} ou { &Variable, PortReception, Taille, Periodicite, "---", 0}
ModuleUse IUSE[] = { IUSE_TERM };

// output data flows : example = { &Variable, PortEmission, Size}
ModuleProduce IPRODUCE[] = { IPRODUCE_TERM };

//input event flows : example = { &Variable, PortReception, size, "module name" (can be unused by setting value to "---"), PortEmission, oneshot}
ModuleReact IREACT [] = { { &controlevent, 0, sizeof(char)*256, "---", 0, 0}, IREACT_TERM };

//output event flows : example = { &variable, PortEmission, size }
ModuleDetect IDETECT [] = { { &message_type_notification, 0, sizeof(TypeC)}, { &received_message, 1, sizeof(TypeE)}, { &connection_status, 2, sizeof(char)*256}, IDETECT_TERM };

// size of parameters that can be received in the request mailbox:
size_t PARAM_SIZE_IN[] = { sizeof(TypeA), PARAM_SIZE_TERM };

// size of parameters or events that can be sent in request mailboxes of other modules (user has to add sizes of sent param requests, if any):

size_t PARAM_SIZE_OUT[] = { /*PROTECTED REGION ID(protect_param_out_MAA) ENABLED START*/ /*PROTECTED REGION END*/PARAM_SIZE_TERM };

//global variables
FILE* logFile;
RTIME productionTime, receptionTime;

//from here you can define new internal variables
/*PROTECTED REGION ID(protect_internal_vars_MAA) ENABLED START*/
int _connected = 0;
double _increment = 1.0;
/*PROTECTED REGION END*/

// Generic Prototypes (to be implemented by the user)
int _init_module(void);//==0 false, != 0 true
void _exit_module(void);
void _exec_module_state(int * stateindex);//state from 0 to x with x > 0, if stateindex is -1 at end of execution then run is finished
void _react_to_event(int eventid , int senderport, char * sender, RTIME * eventProductionTime, RTIME * eventReceptionTime);//to implement to react to some events
void _react_to_parameterizing(int parameterport, RTIME * productionTime, RTIME * receptionTime);//to implement to code reaction on parameterizing actions
//Specific prototypes (from here you can declare new internal functions)
/*PROTECTED REGION ID(protect_internal_functions_decl_MAA) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

int ModuleMain(int argc, const char * argv[])
{
RequestMessage receivedMessage, registered;
int subscription = 0;
int end=0;
int state=0;
int interact,cycleRunning=0;
//log file initialization
time_t log_date; time(&log_date); char* date = ctime(&log_date) ;
char date_jj[5], date_mm[5]; int date_j,date_h,date_m,date_s,date_a;
sscanf(date, "%s %s %d %d:%d:%d %d", date_jj, date_mm, &date_j, &date_h, &date_m, &date_s,&date_a);
char filePath[100];
sprintf(filePath,"%s_%d-%s-%d-%dh%d %ds.csv", MODULE_NAME,date_j, date_mm, date_a, date_h,date_m,date_s);
logFile = fopen(filePath,"at");
if(logFile == NULL) {printf("ERR:%s opening log file(%s)\n",MODULE_NAME, filePath);}

if( _init_module() == 0 ) return(-1);
receivedMessage.Type=REQ_UNKNOWN;
while(!end)
{
switch(receivedMessage.Type)
{
case REQ_UNKNOWN :
if (cycleRunning){
if (state != -1){ //the execution has not been interrupted
//filling the received message with old START request information
receivedMessage.Type=REQ_START;
if ((registered.Param.Start.WantedAck&ACK_NOTHING) == 0)//do not try to copy module names if an ACK is not required
strcpy( receivedMessage.Param.Start.ModAck, registered.Param.Start.ModAck);
receivedMessage.Param.Start.WantedAck= registered.Param.Start.WantedAck;
receivedMessage.Param.Start.AckID = registered.Param.Start.AckID;
}
else { //the execution has been interrupted, waiting again
state = 0;
//sending an acknowledge to the module that has started this module
                                if ((registered.Param.Start.WantedAck &ACK_STOPPED) != 0){
                                SendAck( registered.Param.Start.ModAck, registered.Param.Start.WantedAck,  ACK_STOPPED, registered.Param.Start.AckID);
                                }
                                //reinitializing registered
                                registered.Type=REQ_UNKNOWN;
                                registered.Param.Start.WantedAck = ACK_NOHING;
                                registered.Param.Start.AckID = -1;
                                //waiting a new request
                                WaitForRequest(&receivedMessage);
                                break;
                                }
                                }
                                else {
                                WaitForRequest(&receivedMessage);
                                break;
                                }

                                case REQ_START:
                                if (cycleRunning == 0){//if execution cycle does not run
                                if ((receivedMessage.Param.Start.WantedAck&ACK_START) != 0) //if an ACK is required by the caller
                                SendAck( receivedMessage.Param.Start.ModAck, receivedMessage.Param.Start.WantedAck,  ACK_START, receivedMessage.Param.Start.AckID);
                                }
                                if (subscription == 0){
                                SubscribeVariables();
                                SubscribeEvent();
                                subscription = 1;
                                }
                                interact = 0;
                                cycleRunning = 1;
                                while(!interact){
                                _exec_module_state(&state);
                                if(state==-1){//termination of the run
                                state = 0;
                                cycleRunning = 0;
                                interact = 1;
                                receivedMessage.Type=REQ_UNKNOWN;
                                if((receivedMessage.Param.Start.WantedAck &ACK_FINISHED) != 0) //if an ACK is required by the caller
                                SendAck( receivedMessage.Param.Start.ModAck, receivedMessage.Param.Start.WantedAck,  ACK_FINISHED, receivedMessage.Param.Start.AckID);
                                }
                                if(cycleRunning){
                                //registering the previous request
                                registered.Type=receivedMessage.Type;
                                registered.Param.Start.WantedAck= receivedMessage.Param.Start.WantedAck;
                                registered.Param.Start.AckID = receivedMessage.Param.Start.AckID;
                                if ((registered.Param.Start.WantedAck&ACK_NOHING) == 0)//do not try to copy module names if an ACK is not required
                                strcpy(registered.Param.Start.ModAck, receivedMessage.Param.Start.ModAck);

        // polling on message to be reactive
        if (LookForRequest(&receivedMessage) != NULL)
            interact=1;
    }
}
break;

case REQ_STOP:
if (cycleRunning) {
    state = -1;
    //sending an acknowledge
    if ((receivedMessage.Param.Stop.WantedAck&ACK_STOPPED) != 0)//if an ACK is required
        SendAck( receivedMessage.Param.Stop.ModAck, receivedMessage.Param.Stop.WantedAck,  ACK_STOPPED, receivedMessage.Param.Stop.AckID);
    }
    else {
        state = 0;
        if ((receivedMessage.Param.Stop.WantedAck&ACK_STOPPED) != 0) {//if an ACK is required
            SendAck( receivedMessage.Param.Stop.ModAck, receivedMessage.Param.Stop.WantedAck,  ACK_NOTDONE, receivedMessage.Param.Stop.AckID);
        }
    }
    receivedMessage.Type=REQ_UNKNOWN;
    break;

case REQ_KILL:
    end = 1;
    if ((receivedMessage.Param.Kil.WantedAck&ACK_KILLED) != 0) {//if an ACK is required
        SendAck( receivedMessage.Param.Kil.ModAck, receivedMessage.Param.Kil.WantedAck,  ACK_KILLED, receivedMessage.Param.Kil.AckID);
        receivedMessage.Type=REQ_UNKNOWN;
    }
    break;

case REQ_EVENT:
    _react_to_event(GetEventId(&productionTime, &receptionTime), receivedMessage.Param.Event.sourcePort, &receivedMessage.Param.Event.sourceModule[0], &productionTime, &receptionTime);
    receivedMessage.Type=REQ_UNKNOWN;
    break;

case REQ_SETPARAM:

switch(receivedMessage.Param.SetParam.Port) {
case 0 :
    GetDataFromSetParamRequest(&receivedMessage, &param, sizeof(TypeA), &productionTime, &receptionTime);
    _react_to_parameterizing(0, &productionTime, &receptionTime);
    break;

default:
    printf("Unknown param port:%d\n", receivedMessage.Param.SetParam.Port);
        break;
    }
    receivedMessage.Type=REQ_UNKNOWN;
    break;

    case REQ_SUBSCRIBE:
        SubscribeUser(receivedMessage.Param.Subscribe.SourcePort, receivedMessage.Param.Subscribe.TargetModule, receivedMessage.Param.Subscribe.TargetPort, receivedMessage.Param.Subscribe.Periodicity, receivedMessage.Param.Subscribe.isContextual);
        receivedMessage.Type=REQ_UNKNOWN;
        break;

    case REQ_UNSUBSCRIBE:
        UnsubscribeUser(receivedMessage.Param.Unsubscribe.SourcePort, receivedMessage.Param.Unsubscribe.TargetModule, receivedMessage.Param.Unsubscribe.TargetPort);
        receivedMessage.Type=REQ_UNKNOWN;
        break;
    case REQ_SUB_EVENT:
        SubscribeUserToEvent(receivedMessage.Param.SubscribeEvent.targetModule, receivedMessage.Param.SubscribeEvent.targetPort, receivedMessage.Param.SubscribeEvent.sourcePort, receivedMessage.Param.SubscribeEvent.mode);
        receivedMessage.Type=REQ_UNKNOWN;
        break;

    case REQ_UNSUB_EVENT:
        UnsubscribeUserToEvent(receivedMessage.Param.UnsubscribeEvent.targetModule, receivedMessage.Param.UnsubscribeEvent.targetPort, receivedMessage.Param.UnsubscribeEvent.sourcePort);
        receivedMessage.Type=REQ_UNKNOWN;
        break;

    case REQ_PURGE_MBX:
        PurgeData(NULL);
        receivedMessage.Type=REQ_UNKNOWN;
        break;

    default:
        receivedMessage.Type=REQ_UNKNOWN;
        break;
    }
}
UnsubscribeVariables();
UnsubscribeEvent();
_exit_module();
fclose(logFile);
return 0;
}

int _init_module(void){//==0 false, != 0 true
    /*PROTECTED REGION ID(protect_init_MAA) ENABLED START*/
    printf("initialization of MAA\n");
    _connected = 0;
    return 1;
    /*PROTECTED REGION END*/
}

void _exit_module(void) {
    /*PROTECTED REGION ID(protect_exit_MAA) ENABLED START*/
    printf("termination of MAA\n");
    /*PROTECTED REGION END*/
}

void _exec_module_state(int * stateindex) { //state from 0 to x with x > 0, if stateindex is -1 at end of execution then run is finished
    /*PROTECTED REGION ID(protect_exec_MAA) ENABLED START*/
    char input[256] = "";

    switch(*stateindex) {
    case 0:
        printf("MAA : cycle on state 0\n");
        printf("USER : enter a command : %s\n",
        (_connected==1?"1)disconnection 2) receiving message 3) exiting (and disconnecting) 4) Loop":"1) connection 2) exiting 3) Loop"));
        scanf("%s", &input[0]);

        if (_connected==1) {
            if (strcmp(input, "1")==0) {

                strcpy(connection_status, "disconnected");
                PostEvent(&connection_status[0]);
                printf("disconnection => posting event\n");

                _connected = 0;

            }
            else if (strcmp(input, "2")==0) {

                strcpy(received_message.message.message , "FUFU");

                received_message.message.messagetype = 1;
                received_message.message.value.i = received_message.message.value.i + _increment;
                received_message.message.value.j = received_message.message.value.j + _increment;
                received_message.message.value.k = received_message.message.value.k + _increment;

                strcpy(&received_message.data_.dataname[0], "0");
                received_message.data_.datavalue = 678;

                PostEvent(&received_message);
                printf("posting the whole message is done !\n");

                set_TypeC(&message_type_notification, &received_message.message);

                PostEvent(&message_type_notification);
                printf("posting the message type is done !\n");

            }
            else if (strcmp(input, "3")==0) {
                printf("exitting\n");
                strcpy(connection_status, "disconnected");
                PostEvent(&connection_status[0]);
                printf("disconnection => posting event\n");
                *stateindex = 1;
                _connected = 0;
            }
            else if(strcmp(input, "4")==0){
                printf("loop\n");
            }
            else{
                printf("BAD INPUT : retry\n");
            }
        }
        else{
            if (strcmp(input, "1")==0){
                printf("connection => posting event\n");
                strcpy(connection_status, "connected");
                PostEvent(&connection_status[0]);
                printf("connection => event posted\n");
                _connected = 1;
            }
            else if(strcmp(input, "2")==0){
                printf("exitting\n");
                *stateindex = 1;
            }
            else if(strcmp(input, "3")==0){
                printf("loop\n");
            }
            else{
                printf("BAD INPUT : retry\n");
            }
        }
        break;
    case 1:
        printf("MAA : state 1 => terminal state (do nothing)\n");
        *stateindex = -1;
        break;
    default:
        break;
    }
    /*PROTECTED REGION END*/
}
void _react_to_event(int receiverport , int senderport, char * sendermodule, RTIME * eventProductionTime, RTIME * eventReceptionTime){
    /*PROTECTED REGION ID(protect_event_MAA) ENABLED START*/
    //TODO : implement the code for reaction to event notifications
    /* example pattern for implementing this function
    if (strlen(sendermodule) != 0){//event incoming in a port of the module
        switch(receiverport){
        case 0:
            ...
            break;
        case 1:
            ...
            break;
    }
}
else{//event coming from the specified port of the sender module
    ...
}
*/
/*PROTECTED REGION END*/
}
void _react_to_parameterizing(int parameterport, RTIME * productionTime, RTIME * receptionTime){
    /*PROTECTED REGION ID(protect_param_MAA) ENABLED START*/
    //TODO : implement the code for reaction to parameterizing requests
    /* example pattern for implementing this function
    switch(parameterport){
    case 0:
        ...
        break;
    case 1:
        ...
        break;
    case 2:
        ...
        break;
    }
    */
    /*PROTECTED REGION END*/
}
//Specific functions (from here you have to implement new internal functions declared before main)
/*PROTECTED REGION ID(protect_internal_functions_impl_MAA) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

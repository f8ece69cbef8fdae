/* The list of C tests (included by runner.c only). */
#ifndef TESTS_H
#define TESTS_H
#include "harness.h"
void test_tools_parse(void);
void test_tools_serialize(void);
void test_tools_bool_enum(void);
void test_ext_types_round_trip(void);
void test_msc_request_loop(void);
void test_run_cpu_time(void);
void test_msc_setparam_event(void);
void test_stop_running_cycle(void);
void test_data_periodicity(void);
void test_event_oneshot_continuous(void);
void test_setparam_sizes(void);
void test_malformed_datagrams(void);
void test_producer_change_and_interleave(void);
void test_unknown_and_stale(void);
void test_request_to_gone_while_stopping(void);
void test_peer_gone_at_stop(void);
void test_nonblocking_sends(void);
void test_queued_sends(void);
void test_error_repeats(void);
void test_queued_sends_room(void);
void test_sockets_above_stdio(void);
void test_long_run_dir(void);
void test_maa_events_params(void);
void test_unsub_spent_oneshot(void);
void test_status_running(void);
void test_status_through_signals(void);
void test_ask_module_priority(void);
void test_status_behind_requests(void);
void test_launcher_crash_cleanup(void);
void test_launcher_start_duration(void);
void test_launcher_module_ends(void);
void test_launcher_sigint(void);
void test_launcher_stop_why(void);
void test_kill_without_launcher(void);
void test_launcher_end_by(void);
void test_launcher_output_limit(void);
void test_launcher_stop_budget(void);
void test_stop_signal_at_startup(void);
void test_launcher_placement(void);
void test_launcher_module_bound(void);
void test_launcher_require_realtime(void);
void test_two_run_dirs(void);
void test_control_tool(void);
void test_priority(void);
void test_set_module_priority(void);
void test_csv_log_cap(void);
void test_csv_log_mark(void);
void test_csv_log_mark_delay(void);
void test_csv_log_flush_boundary(void);
void test_csv_log_crash(void);
void test_crash_report(void);
void test_csv_log_crash_writer_busy(void);
void test_csv_log_writer_thread(void);
void test_csv_log_writer_refused(void);
void test_csv_log_fork_child(void);
void test_csv_log_record_bounds(void);
void test_csv_log_event_not_a_word(void);
void test_csv_log_engine_kinds(void);
void test_csv_log_disk_full(void);
void test_csv_log_disk_reserve(void);
void test_csv_log_reserve_overshoot(void);
void test_csv_log_killed(void);

static const TestCase ALL_TESTS[] = {
    { "tools_parse", test_tools_parse },
    { "tools_serialize", test_tools_serialize },
    { "tools_bool_enum", test_tools_bool_enum },
    { "msc_request_loop", test_msc_request_loop },
    { "run_cpu_time", test_run_cpu_time },
    { "msc_setparam_event", test_msc_setparam_event },
    { "stop_running_cycle", test_stop_running_cycle },
    { "data_periodicity", test_data_periodicity },
    { "event_oneshot_continuous", test_event_oneshot_continuous },
    { "setparam_sizes", test_setparam_sizes },
    { "malformed_datagrams", test_malformed_datagrams },
    { "producer_change_and_interleave", test_producer_change_and_interleave },
    { "unknown_and_stale", test_unknown_and_stale },
    { "request_to_gone_while_stopping", test_request_to_gone_while_stopping },
    { "peer_gone_at_stop", test_peer_gone_at_stop },
    { "nonblocking_sends", test_nonblocking_sends },
    { "queued_sends", test_queued_sends },
    { "error_repeats", test_error_repeats },
    { "queued_sends_room", test_queued_sends_room },
    { "sockets_above_stdio", test_sockets_above_stdio },
    { "long_run_dir", test_long_run_dir },
    { "maa_events_params", test_maa_events_params },
    { "unsub_spent_oneshot", test_unsub_spent_oneshot },
    { "status_running", test_status_running },
    { "status_through_signals", test_status_through_signals },
    { "ask_module_priority", test_ask_module_priority },
    { "status_behind_requests", test_status_behind_requests },
    { "launcher_crash_cleanup", test_launcher_crash_cleanup },
    { "launcher_start_duration", test_launcher_start_duration },
    { "launcher_module_ends", test_launcher_module_ends },
    { "launcher_sigint", test_launcher_sigint },
    { "launcher_stop_why", test_launcher_stop_why },
    { "kill_without_launcher", test_kill_without_launcher },
    { "launcher_end_by", test_launcher_end_by },
    { "launcher_output_limit", test_launcher_output_limit },
    { "launcher_stop_budget", test_launcher_stop_budget },
    { "stop_signal_at_startup", test_stop_signal_at_startup },
    { "launcher_placement", test_launcher_placement },
    { "launcher_module_bound", test_launcher_module_bound },
    { "launcher_require_realtime", test_launcher_require_realtime },
    { "two_run_dirs", test_two_run_dirs },
    { "control_tool", test_control_tool },
    { "priority", test_priority },
    { "set_module_priority", test_set_module_priority },
    { "csv_log_cap", test_csv_log_cap },
    { "csv_log_mark", test_csv_log_mark },
    { "csv_log_mark_delay", test_csv_log_mark_delay },
    { "csv_log_flush_boundary", test_csv_log_flush_boundary },
    { "csv_log_crash", test_csv_log_crash },
    { "crash_report", test_crash_report },
    { "csv_log_crash_writer_busy", test_csv_log_crash_writer_busy },
    { "csv_log_writer_thread", test_csv_log_writer_thread },
    { "csv_log_writer_refused", test_csv_log_writer_refused },
    { "csv_log_fork_child", test_csv_log_fork_child },
    { "csv_log_record_bounds", test_csv_log_record_bounds },
    { "csv_log_event_not_a_word", test_csv_log_event_not_a_word },
    { "csv_log_engine_kinds", test_csv_log_engine_kinds },
    { "csv_log_disk_full", test_csv_log_disk_full },
    { "csv_log_disk_reserve", test_csv_log_disk_reserve },
    { "csv_log_reserve_overshoot", test_csv_log_reserve_overshoot },
    { "csv_log_killed", test_csv_log_killed },
    { "ext_types_round_trip", test_ext_types_round_trip },
    { NULL, NULL },
};
#endif

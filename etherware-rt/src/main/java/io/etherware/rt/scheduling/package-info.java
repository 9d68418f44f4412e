/**
 * The real-time Dispatching Module (paper Section IV-B, Fig. 4): dispatchers at fixed OS
 * priorities ({@link io.etherware.rt.scheduling.ThreadSchedulingRule}), the policy that places
 * each job on one of them with a queue key ({@link io.etherware.rt.scheduling.JobPlacementRule}),
 * time accounting ({@link io.etherware.rt.scheduling.SchedulerStats}, JFR events
 * {@code io.etherware.rt.Dispatch} and {@code io.etherware.rt.DeadlineMiss}) and admission control
 * for declared periodic streams.
 *
 * <pre>{@code
 * var scheduler = new RealtimeScheduler(RealtimeSchedulerConfig.builder()
 *         .threadSchedulingRule(ThreadSchedulingRule.tableII())   // 0: SCHED_OTHER, 1..3: SCHED_FIFO 80/70/60
 *         .placementRule(new CriticalityDeadlinePlacement())     // Algorithm 1
 *         .admissionMode(AdmissionMode.REJECT)
 *         .build());
 * scheduler.admission().declare(PeriodicStream.of(Profile.of("controller"), Criticality.HIGH,
 *         15_000_000L, 2_000_000L));                              // period 15 ms, WCET 2 ms
 * }</pre>
 *
 * The scheduler is then handed to the node in place of the original FIFO dispatcher; the kernel
 * does not change with the policy.
 */
package io.etherware.rt.scheduling;

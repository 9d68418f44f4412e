package io.etherware.rt.scheduling;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.QoS;
import io.etherware.core.time.NodeClock;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * A child JVM for {@link PlatformRefusalChildJvmTest}: starts the default real-time scheduler
 * (optionally locking memory), runs one HIGH job, prints the platform report and the locked
 * memory, and exits. Output lines are prefixed so the parent can pick them out.
 */
public final class SchedulerProbeMain {

    private SchedulerProbeMain() {
    }

    public static void main(String[] args) throws Exception {
        boolean lockMemory = args.length > 0 && args[0].equals("lock");
        var ran = new CountDownLatch(1);
        var scheduler = new RealtimeScheduler(RealtimeSchedulerConfig.builder().lockMemory(lockMemory).build());
        scheduler.start((job, nowNs) -> {
            ran.countDown();
            return true;
        }, NodeClock.system());
        scheduler.submit(TestJobs.job("probe", QoS.of(Criticality.HIGH), System.nanoTime()));
        System.out.println(ran.await(10, TimeUnit.SECONDS) ? "RAN HIGH" : "HIGH NOT RUN");
        scheduler.platformReport().lines().forEach(line -> System.out.println("REPORT " + line));
        for (String line : Files.readAllLines(Path.of("/proc/self/status"))) {
            if (line.startsWith("VmLck:")) {
                System.out.println("VMLCK " + line.substring(6).strip());
            }
        }
        scheduler.shutdown(TimeUnit.SECONDS.toNanos(1));
    }
}

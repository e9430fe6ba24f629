/* A ground client of visnavd's telemetry written only against what visnav-dev installs: the idlc header
 * <visnav/idl/visnav.h> and libvisnav-idl (the topic descriptor visnav_PoseEstimate_desc), plus the system's
 * Cyclone DDS. Subscribes to visnav_pose with the reader QoS of fsw/telemetry/README.md (reliable, keep-last,
 * volatile) in the given domain and partition, and exits 0 after COUNT samples whose sample_number rises and
 * whose fields are in range; 1 on a timeout or a bad sample, 2 on a usage or DDS error.
 *   visnav_pose_client DOMAIN PARTITION COUNT TIMEOUT_S
 * Built by tests/package/test_dev_client.sh twice: with pkg-config (visnav-idl) and with CMake
 * (find_package(visnav-idl), CMakeLists.txt beside this file). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dds/dds.h"
#include "visnav/idl/visnav.h"

int main(int argc, char** argv) {
  if (argc != 5) {
    fprintf(stderr, "usage: %s DOMAIN PARTITION COUNT TIMEOUT_S\n", argv[0]);
    return 2;
  }
  const dds_domainid_t domain = (dds_domainid_t)strtoul(argv[1], NULL, 10);
  const char* partition = argv[2];
  const long wanted = strtol(argv[3], NULL, 10);
  const double timeout_s = strtod(argv[4], NULL);

  const dds_entity_t participant = dds_create_participant(domain, NULL, NULL);
  if (participant < 0) {
    fprintf(stderr, "dds_create_participant: %s\n", dds_strretcode(-participant));
    return 2;
  }
  dds_qos_t* qos = dds_create_qos();
  const char* partitions[1] = {partition};
  dds_qset_partition(qos, 1, partitions);
  const dds_entity_t subscriber = dds_create_subscriber(participant, qos, NULL);
  dds_reset_qos(qos);
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 16);
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  const dds_entity_t topic =
      dds_create_topic(participant, &visnav_PoseEstimate_desc, "visnav_pose", NULL, NULL);
  const dds_entity_t reader = dds_create_reader(subscriber, topic, qos, NULL);
  /* Readers on the other two flight topics too (a ground client watches health as well), so that
   * `visnavd --wait-subscribers N` counts this client on every topic it publishes. */
  const dds_entity_t far_topic =
      dds_create_topic(participant, &visnav_FarRangeEstimate_desc, "visnav_far_range", NULL, NULL);
  const dds_entity_t far_reader = dds_create_reader(subscriber, far_topic, qos, NULL);
  dds_qset_durability(qos, DDS_DURABILITY_TRANSIENT_LOCAL);
  const dds_entity_t health_topic =
      dds_create_topic(participant, &visnav_Health_desc, "visnav_health", NULL, NULL);
  const dds_entity_t health_reader = dds_create_reader(subscriber, health_topic, qos, NULL);
  dds_delete_qos(qos);
  if (subscriber < 0 || topic < 0 || reader < 0 || far_reader < 0 || health_reader < 0) {
    fprintf(stderr, "subscriber/topic/readers: %d %d %d %d %d\n", subscriber, topic, reader, far_reader,
            health_reader);
    dds_delete(participant);
    return 2;
  }
  const dds_entity_t waitset = dds_create_waitset(participant);
  const dds_entity_t readcond = dds_create_readcondition(reader, DDS_ANY_STATE);
  dds_waitset_attach(waitset, readcond, 0);

  const dds_time_t deadline = dds_time() + (dds_duration_t)(timeout_s * 1e9);
  long received = 0;
  unsigned long long last_sample_number = 0;
  int status = 1;
  while (received < wanted && dds_time() < deadline) {
    dds_waitset_wait_until(waitset, NULL, 0, deadline);
    visnav_PoseEstimate sample;
    void* samples[1] = {&sample};
    dds_sample_info_t info;
    while (received < wanted && dds_take(reader, samples, &info, 1, 1) == 1) {
      if (!info.valid_data) continue;
      const int finite = isfinite(sample.position_m[0]) && isfinite(sample.position_m[1]) &&
                         isfinite(sample.position_m[2]) && isfinite(sample.quaternion[0]);
      const int sane = sample.sample_number > last_sample_number &&
                       sample.mode <= visnav_NAV_MODE_NEAR_RANGE && sample.status <= visnav_TRACK_INIT &&
                       finite;
      printf("pose sample_number %llu frame %llu mode %u status %u t_c_m %.3f %.3f %.3f m\n",
             (unsigned long long)sample.sample_number, (unsigned long long)sample.frame_number,
             (unsigned)sample.mode, (unsigned)sample.status, sample.position_m[0], sample.position_m[1],
             sample.position_m[2]);
      if (!sane) {
        fprintf(stderr, "bad sample (after sample_number %llu)\n", last_sample_number);
        dds_delete(participant);
        return 1;
      }
      last_sample_number = sample.sample_number;
      ++received;
    }
  }
  if (received >= wanted) status = 0;
  printf("received %ld of %ld PoseEstimate samples on domain %u partition %s\n", received, wanted,
         (unsigned)domain, partition);
  dds_delete(participant);
  return status;
}
